// Row prediction of a tile's RGB8 bytes, before zstd (tile_t::ZSTD_UP_RGB8). A shaded picture
// changes little from one row to the next, so each byte is sent as its difference from the byte
// one row above (the first row: from the pixel to its left), modulo 256. The differences are
// mostly near 0, which zstd packs far tighter than the pixels themselves: about 40 % fewer bytes
// on the default breeze's changed tiles. The pixel hash stays that of the pixels.
//
//   residual[r][i] = pixel[r][i] - pixel[r - 1][i]   (r > 0)
//   residual[0][i] = pixel[0][i] - pixel[0][i - 3]   (i >= 3; the first pixel as it is)
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace flagsim {

/// The residuals of `pixels`: `width` RGB8 pixels a row, rows top to bottom.
inline std::vector<uint8_t> PredictRows(const std::vector<uint8_t>& pixels, int width) {
  const size_t stride = size_t(width) * 3;
  std::vector<uint8_t> residuals(pixels.size());
  for (size_t i = 0; i < pixels.size(); ++i) {
    const uint8_t prediction = i >= stride ? pixels[i - stride] : (i >= 3 ? pixels[i - 3] : 0);
    residuals[i] = static_cast<uint8_t>(pixels[i] - prediction);
  }
  return residuals;
}

/// The pixels back from their residuals, in place.
inline void UnpredictRows(int width, std::vector<uint8_t>* bytes) {
  std::vector<uint8_t>& b = *bytes;
  const size_t stride = size_t(width) * 3;
  for (size_t i = 3; i < std::min(stride, b.size()); ++i) b[i] = static_cast<uint8_t>(b[i] + b[i - 3]);
  for (size_t i = stride; i < b.size(); ++i) b[i] = static_cast<uint8_t>(b[i] + b[i - stride]);
}

}  // namespace flagsim
