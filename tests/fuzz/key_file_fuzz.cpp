// Fuzz target: the key file reader (messages/command_key.hpp ReadKeyFile), as flagd and flagctl
// read --key-file. The input is the file, held with the owner-only mode a key file must have.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "messages/command_key.hpp"
#include "tests/fuzz/scratch_file.hpp"

using namespace flagsim;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static fuzz::ScratchFile file("key_file", 0600);
  try {
    ReadKeyFile(file.Hold(data, size));
  } catch (const std::runtime_error&) {
    // refused, naming the file and the line: what a bad key file should get
  }
  return 0;
}
