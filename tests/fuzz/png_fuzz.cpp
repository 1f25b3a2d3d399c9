// Fuzz target: the PNG reader (common/png_file.hpp ReadPng). The input is the file.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/png_file.hpp"
#include "tests/fuzz/scratch_file.hpp"

using namespace flagsim;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static fuzz::ScratchFile file("png");
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
  ReadPng(file.Hold(data, size), &width, &height, &rgb);
  return 0;
}
