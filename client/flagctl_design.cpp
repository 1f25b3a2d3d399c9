// flagctl design NAME|FILE: the flag's design. A built-in one by name goes as the `design`
// parameter (PARAM), journaled, replayed and reset like every parameter; a person's image (a
// PNG or JPEG file) is checked here, then sent in pieces (design_upload.hpp), and the flag's
// width follows its aspect unless a width was set.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "client/design_upload.hpp"
#include "client/flagctl_commands.hpp"
#include "client/flagctl_link.hpp"
#include "common/design_image.hpp"

namespace flagsim {
namespace {

/// A file is what exists, or what has a folder or an extension in its name; anything else is a
/// built-in design's name, which the server checks.
bool NamesAFile(const std::string& argument) {
  std::error_code ignored;
  const std::filesystem::path path(argument);
  return std::filesystem::exists(path, ignored) || path.has_extension() ||
         argument.find('/') != std::string::npos;
}

int SendImage(const Globals& globals, const std::string& path) {
  std::vector<uint8_t> bytes;
  std::string problem = ReadDesignFile(path, &bytes);
  if (problem.empty()) problem = CheckDesignFile(bytes);
  if (!problem.empty()) {
    std::fprintf(stderr, "flagctl: design %s: %s\n", path.c_str(), problem.c_str());
    return kUsage;
  }
  Link link(globals);
  CommandClient client(link.bus, link.channels, globals.timeout, link.signer);
  const std::string name = std::filesystem::path(path).filename().string();
  return Report(link, SendDesignFile(client, link.channels.design, name, bytes));
}

}  // namespace

void AddDesignCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* design = app.add_subcommand(
      "design",
      "show a built-in design on the flag (the design parameter), or a PNG or JPEG file of your own");
  auto name = std::make_shared<std::string>();
  design
      ->add_option(
          "NAME|FILE", *name,
          "nordic_cross, tricolour or checker; or an image file: its transparent pixels cut the flag's "
          "outline, and the flag's width follows its aspect unless a width was set")
      ->required();
  invocation.RunOnParse(design, [&invocation, name] {
    if (!NamesAFile(*name)) return SendParams(invocation.globals, {"design=" + *name}, false);
    return SendImage(invocation.globals, *name);
  });
}

}  // namespace flagsim
