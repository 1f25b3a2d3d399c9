// The image a frame is drawn into: RGB8 colour and a float depth buffer, rows top to bottom.
#pragma once

#include <cstdint>
#include <vector>

namespace flagsim::render {

struct Framebuffer {
  int width = 0;             ///< px
  int height = 0;            ///< px
  std::vector<uint8_t> rgb;  ///< 3 bytes per pixel, row-major, top row first
  std::vector<float> depth;  ///< window depth per pixel, 0 (near) .. 1 (far)

  void Resize(int new_width, int new_height) {
    width = new_width;
    height = new_height;
    rgb.assign(size_t(width) * height * 3, 0);
    depth.assign(size_t(width) * height, 1.0f);
  }
  uint8_t* Pixel(int x, int y) { return &rgb[(size_t(y) * width + x) * 3]; }
  const uint8_t* Pixel(int x, int y) const { return &rgb[(size_t(y) * width + x) * 3]; }
};

}  // namespace flagsim::render
