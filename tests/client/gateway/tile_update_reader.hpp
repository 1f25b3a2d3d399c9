// Reads flagsim.TileUpdate messages as a client would (docs/live-view.md): applies each tile to
// an RGB8 image after checking its pixel hash, then checks the whole image against the frame
// hash. Written from the layout in the docs, not from the gateway's code.
#pragma once

#include <xxhash.h>
#include <zstd.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace flagsim::gateway::testing {

class TileUpdateReader {
 public:
  /// Applies `update`; "" or what was wrong with it.
  std::string Apply(const std::string& update) {
    if (update.size() < 48 || uint8_t(update[0]) != 1) return "bad head";
    keyframe_ = update[1] != 0;
    const int tile_size = U16(update, 2);
    const int width = int(U32(update, 4)), height = int(U32(update, 8));
    const uint32_t count = U32(update, 12);
    frame_id_ = int64_t(U64(update, 16));
    frame_hash_ = U64(update, 40);
    if (width != width_ || height != height_) {
      if (!keyframe_) return "a new size without a keyframe";
      width_ = width;
      height_ = height;
      image_.assign(size_t(width) * height * 3, 0);
    }
    size_t at = 48;
    tiles_ = count;
    for (uint32_t t = 0; t < count; ++t) {
      if (at + 27 > update.size()) return "truncated tile head";
      const int x = U16(update, at + 4), y = U16(update, at + 6), w = U16(update, at + 8),
                h = U16(update, at + 10);
      const int encoding = uint8_t(update[at + 12]);
      const uint64_t hash = U64(update, at + 13);
      const uint32_t bytes = U32(update, at + 21);
      at += 25;
      if (at + bytes > update.size()) return "truncated tile bytes";
      if (x + w > width_ || y + h > height_ || w > tile_size || h > tile_size) return "tile out of the image";
      std::vector<uint8_t> pixels(size_t(w) * h * 3);
      if (encoding == 1 || encoding == 2) {
        if (ZSTD_decompress(pixels.data(), pixels.size(), update.data() + at, bytes) != pixels.size()) {
          return "tile does not decompress";
        }
        if (encoding == 2) AddRowsBack(w, &pixels);
      } else if (bytes == pixels.size()) {
        std::memcpy(pixels.data(), update.data() + at, bytes);
      } else {
        return "raw tile of the wrong size";
      }
      if (XXH3_64bits(pixels.data(), pixels.size()) != hash) return "tile hash mismatch";
      for (int row = 0; row < h; ++row) {
        std::memcpy(&image_[(size_t(y + row) * width_ + x) * 3], &pixels[size_t(row) * w * 3], size_t(w) * 3);
      }
      at += bytes;
    }
    if (at != update.size()) return "bytes after the last tile";
    return XXH3_64bits(image_.data(), image_.size()) == frame_hash_ ? "" : "frame hash mismatch";
  }

  const std::vector<uint8_t>& image() const { return image_; }
  int64_t frame_id() const { return frame_id_; }
  int width() const { return width_; }
  bool keyframe() const { return keyframe_; }
  uint32_t tiles() const { return tiles_; }

 private:
  /// Encoding 2: each byte plus the byte one row up (in the first row, one pixel left), mod 256.
  static void AddRowsBack(int width, std::vector<uint8_t>* pixels) {
    std::vector<uint8_t>& p = *pixels;
    const size_t row = size_t(width) * 3;
    for (size_t i = 0; i < p.size(); ++i) {
      if (i >= row) {
        p[i] = uint8_t(p[i] + p[i - row]);
      } else if (i >= 3) {
        p[i] = uint8_t(p[i] + p[i - 3]);
      }
    }
  }
  static uint16_t U16(const std::string& b, size_t at) {
    return uint16_t(uint8_t(b[at]) | uint8_t(b[at + 1]) << 8);
  }
  static uint32_t U32(const std::string& b, size_t at) { return U16(b, at) | uint32_t(U16(b, at + 2)) << 16; }
  static uint64_t U64(const std::string& b, size_t at) { return U32(b, at) | uint64_t(U32(b, at + 4)) << 32; }

  int width_ = 0, height_ = 0;
  std::vector<uint8_t> image_;
  int64_t frame_id_ = -1;
  uint64_t frame_hash_ = 0;
  bool keyframe_ = false;
  uint32_t tiles_ = 0;
};

}  // namespace flagsim::gateway::testing
