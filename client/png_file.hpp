// Writing and reading RGB8 images as PNG (libpng).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace flagsim {

/// Writes width x height RGB8 pixels (rows top to bottom) to `path`; "" or what went wrong.
std::string WritePng(const std::string& path, int width, int height, const uint8_t* rgb);

/// Reads an 8-bit RGB PNG; "" or what went wrong.
std::string ReadPng(const std::string& path, int* width, int* height, std::vector<uint8_t>* rgb);

}  // namespace flagsim
