// flagctl keygen: a new key file for signed commands (messages/command_key.hpp). The same file
// goes to flagd --key-file and to each client's --key-file; only its owner can read it.
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "client/flagctl_commands.hpp"
#include "messages/command_key.hpp"

namespace flagsim {
namespace {

int Keygen(const std::string& path, const std::string& name) {
  const std::string bad_name = CheckKeyName(name);
  if (!bad_name.empty()) {
    std::fprintf(stderr, "flagctl: --name: %s\n", bad_name.c_str());
    return kUsage;
  }
  try {
    WriteNewKeyFile(path, name);
  } catch (const std::runtime_error& error) {
    std::fprintf(stderr, "flagctl: %s\n", error.what());
    return kFailed;
  }
  std::printf(
      "%s: key '%s' (32 random bytes), readable by you only.\n"
      "Give it to the server (flagd --key-file %s) and to each client that may steer it\n"
      "(flagctl --key-file %s, also for flagctl serve); copy it only over a private channel.\n",
      path.c_str(), name.c_str(), path.c_str(), path.c_str());
  return kOk;
}

}  // namespace

void AddKeygenCommand(CLI::App& app, Invocation& invocation) {
  struct Arguments {
    std::string path, name = "flagsim";
  };
  auto arguments = std::make_shared<Arguments>();
  CLI::App* keygen = app.add_subcommand(
      "keygen", "write a new key file for signed commands (flagd --key-file, flagctl --key-file)");
  keygen->add_option("-o,--output", arguments->path, "the key file to create (never overwritten; mode 600)")
      ->required();
  keygen->add_option("--name", arguments->name, "the key's name, which commands carry and logs show")
      ->capture_default_str();
  keygen->footer("Exit codes: 0 written, 1 the file exists or cannot be written, 2 usage (a bad name).");
  invocation.RunOnParse(keygen, [arguments] { return Keygen(arguments->path, arguments->name); });
}

}  // namespace flagsim
