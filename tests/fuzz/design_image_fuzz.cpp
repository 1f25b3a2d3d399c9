// Fuzz target: a person's image for the flag's design, as the server takes it when its pieces
// are whole (server/scene/design_file.hpp MakeDesignFile: the checks of common/design_image.hpp,
// PNG or JPEG decoding, the texture filtered down). The input is the file.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "server/scene/design_file.hpp"

using namespace flagsim;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  DesignFilePtr file;
  if (MakeDesignFile("fuzz.png", std::vector<uint8_t>(data, data + size), &file).empty() &&
      (!file || file->texture.width < 1 || file->texture.width > DesignFile::kMaxTexels))
    __builtin_trap();  // a file taken must have made a texture within the cap
  return 0;
}
