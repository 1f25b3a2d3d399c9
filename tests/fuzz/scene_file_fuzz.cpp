// Fuzz target: the scene reader as flagd takes a scene (flagd --scene FILE --set NAME=VALUE):
// TOML text through ParseScene (parameters, wind, camera, timeline keys, each checked by the
// table that checks commands), then each --set assignment through the parameter table, then the
// rules that join parameters. The input is the file's text, then optionally a NUL byte and the
// assignments, one NAME=VALUE a line.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "server/scene/parameter_table.hpp"
#include "server/scene/scene_file.hpp"

using namespace flagsim;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const size_t split = input.find('\0');
  Scene scene;
  try {
    scene = ParseScene(input.substr(0, split), "fuzz.toml");
  } catch (const SceneError&) {
    return 0;  // refused, with its reason: what a bad file should get
  }
  if (split == std::string::npos) return 0;
  std::istringstream assignments(input.substr(split + 1));
  std::string line;
  while (std::getline(assignments, line)) {
    const size_t equals = line.find('=');
    if (equals == std::string::npos) continue;
    if (!ParameterTable::Get().Assign(line.substr(0, equals), line.substr(equals + 1), &scene).empty())
      return 0;
  }
  ParameterTable::CheckConsistency(scene);
  return 0;
}
