// One picture into a file whose name says its format (flagctl snapshot):
//
//   NAME.png               PNG (lossless)
//   NAME.jpg, NAME.jpeg    JPEG, quality kJpegFileQuality
//
// Any other name is refused before anything is asked of the server.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace flagsim {

enum class PictureFormat { kPng, kJpeg };

/// The format `path`'s extension names (any letter case); nullopt with *error naming what is
/// allowed if none.
std::optional<PictureFormat> PictureFormatOf(const std::string& path, std::string* error);

/// Writes `width` x `height` RGB8 pixels to `path` in `format`; "" or what went wrong.
std::string WritePicture(const std::string& path, PictureFormat format, int width, int height,
                         const uint8_t* rgb);

}  // namespace flagsim
