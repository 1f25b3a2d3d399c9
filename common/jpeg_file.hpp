// Writing RGB8 images as JPEG (libjpeg): flagctl snapshot's .jpg files, the live view's
// Foxglove image channel.
#pragma once

#include <cstdint>
#include <string>

namespace flagsim {

constexpr int kJpegFileQuality = 90;  ///< 0 .. 100, for files a user keeps

/// The JPEG bytes of `width` x `height` RGB8 pixels (rows top to bottom, no padding).
std::string EncodeJpeg(const uint8_t* rgb, int width, int height, int quality);

/// Writes the pixels to `path` as a JPEG file; "" or what went wrong.
std::string WriteJpeg(const std::string& path, int width, int height, const uint8_t* rgb,
                      int quality = kJpegFileQuality);

}  // namespace flagsim
