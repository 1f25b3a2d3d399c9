// Writing and reading RGB8 images as PNG (libpng).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace flagsim {

/// Writes width x height RGB8 pixels (rows top to bottom) to `path`; "" or what went wrong.
std::string WritePng(const std::string& path, int width, int height, const uint8_t* rgb);

/// "DIR/frame_000042.png": frame `index` of a numbered sequence in `directory`, as flagd render
/// and flagctl export write them.
std::string PngFramePath(const std::string& directory, int64_t index);

/// px: the widest and tallest PNG ReadPng takes, as the largest frame a client assembles.
constexpr int kMaxPngSide = 8192;

/// Reads a PNG (any colour type and depth) as 8-bit RGB; "" or what went wrong. One wider or
/// taller than kMaxPngSide is refused before its pixels are read.
std::string ReadPng(const std::string& path, int* width, int* height, std::vector<uint8_t>* rgb);

}  // namespace flagsim
