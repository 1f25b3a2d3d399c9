// A person's own image for the flag's design: a PNG or JPEG file, checked against the limits
// before any pixel is decoded, then decoded to 8-bit RGBA. Both programs use it: flagctl to
// refuse a bad file before sending it, flagd to check what arrived.
//
//   bytes => sniff the signature (PNG, JPEG) => header: width, height => limits => decode
//
// The header alone says the size: a few bytes may claim gigabytes of pixels, so the limits
// are checked on it, and the decoder never allocates more than kMaxDesignPixels * 4 bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace flagsim {

constexpr size_t kMaxDesignFileBytes = 4u << 20;  ///< 4 MiB
constexpr int kMaxDesignSide = 8192;              ///< px, either side
constexpr int64_t kMaxDesignPixels = 16 << 20;    ///< 16 Mpx (4096 x 4096)

/// The limits in words, for the errors that name them.
std::string DesignLimits();

enum class ImageFormat { kPng, kJpeg };

struct ImageHeader {
  ImageFormat format = ImageFormat::kPng;
  int width = 0, height = 0;  ///< px
};

/// "" and the header of a PNG or JPEG file within the limits, or what is wrong: empty, too large
/// in bytes, not a PNG or JPEG, a header that cannot be read, too large in pixels.
std::string InspectDesignImage(const uint8_t* data, size_t size, ImageHeader* header);

struct RgbaImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  ///< row-major, top row first; sRGB colour, straight (unpremultiplied) alpha

  /// Whether any pixel is less than opaque.
  bool HasTransparency() const;
};

/// Inspects, then decodes the whole file; "" or what is wrong (a truncated or damaged file
/// included), then `*image` is untouched.
std::string DecodeDesignImage(const uint8_t* data, size_t size, RgbaImage* image);

/// The file at `path` into `*bytes`, refused before it is read if larger than the limit; "" or
/// what went wrong (naming the path).
std::string ReadDesignFile(const std::string& path, std::vector<uint8_t>* bytes);

/// The SHA-256 of `size` bytes, as 64 lowercase hex digits: a design file's identity on the wire.
std::string Sha256Hex(const uint8_t* data, size_t size);

}  // namespace flagsim
