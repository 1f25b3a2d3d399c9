// Image files made in memory for the tests of a person's design: PNG (RGBA) and JPEG bytes.
#pragma once

#include <png.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/jpeg_file.hpp"

namespace flagsim::testing {

/// width x height pixels of one RGBA colour.
inline std::vector<uint8_t> SolidRgba(int width, int height, uint8_t r, uint8_t g, uint8_t b,
                                      uint8_t a = 255) {
  std::vector<uint8_t> rgba(size_t(width) * height * 4);
  for (size_t i = 0; i < rgba.size(); i += 4) {
    rgba[i] = r;
    rgba[i + 1] = g;
    rgba[i + 2] = b;
    rgba[i + 3] = a;
  }
  return rgba;
}

/// The PNG file of width x height RGBA pixels.
inline std::vector<uint8_t> PngBytes(int width, int height, const std::vector<uint8_t>& rgba) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32(width);
  image.height = png_uint_32(height);
  image.format = PNG_FORMAT_RGBA;
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&image, nullptr, &size, 0, rgba.data(), 0, nullptr))
    throw std::runtime_error("libpng: cannot size the PNG");
  std::vector<uint8_t> bytes(size);
  if (!png_image_write_to_memory(&image, bytes.data(), &size, 0, rgba.data(), 0, nullptr))
    throw std::runtime_error("libpng: cannot write the PNG");
  bytes.resize(size);
  return bytes;
}

/// The JPEG file of width x height pixels of one colour.
inline std::vector<uint8_t> JpegBytes(int width, int height, uint8_t r, uint8_t g, uint8_t b) {
  std::vector<uint8_t> rgb(size_t(width) * height * 3);
  for (size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = r;
    rgb[i + 1] = g;
    rgb[i + 2] = b;
  }
  const std::string jpeg = EncodeJpeg(rgb.data(), width, height, 95);
  return std::vector<uint8_t>(jpeg.begin(), jpeg.end());
}

}  // namespace flagsim::testing
