// A whole frame as a foxglove.CompressedImage: the RGB8 image compressed to JPEG (libjpeg),
// carried in JSON as base64, as Foxglove's image panel and Lichtblick read it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace flagsim::gateway {

constexpr int kJpegQuality = 85;  ///< 0..100

/// A JPEG file of `width` x `height` RGB8 pixels (rows top to bottom, no padding).
std::string EncodeJpeg(const uint8_t* rgb, int width, int height, int quality = kJpegQuality);

/// RFC 4648 base64, with padding.
std::string Base64(std::string_view bytes);

/// The JSON text of a foxglove.CompressedImage holding `jpeg`, stamped with `utime`
/// (us since the Unix epoch).
std::string CompressedImageJson(const std::string& jpeg, int64_t utime);

}  // namespace flagsim::gateway
