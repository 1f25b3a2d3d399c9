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

/// The residuals of `pixels` (`width` RGB8 pixels a row, rows top to bottom) into `residuals`.
inline void PredictRows(const std::vector<uint8_t>& pixels, int width, std::vector<uint8_t>* residuals) {
  const size_t size = pixels.size(), stride = std::min(size_t(width) * 3, size);
  residuals->resize(size);
  const uint8_t* __restrict p = pixels.data();
  uint8_t* __restrict r = residuals->data();
  for (size_t i = 0; i < std::min<size_t>(3, size); ++i) r[i] = p[i];
  for (size_t i = 3; i < stride; ++i) r[i] = static_cast<uint8_t>(p[i] - p[i - 3]);
  for (size_t i = stride; i < size; ++i) r[i] = static_cast<uint8_t>(p[i] - p[i - stride]);  // vectorises
}

/// The pixels back from their residuals, in place.
inline void UnpredictRows(int width, std::vector<uint8_t>* bytes) {
  uint8_t* b = bytes->data();
  const size_t size = bytes->size(), stride = std::min(size_t(width) * 3, size);
  for (size_t i = 3; i < stride; ++i) b[i] = static_cast<uint8_t>(b[i] + b[i - 3]);
  for (size_t row = stride; row < size; row += stride) {  // each row from the one above, vectorised
    const uint8_t* __restrict above = b + row - stride;
    uint8_t* __restrict here = b + row;
    for (size_t i = 0; i < std::min(stride, size - row); ++i)
      here[i] = static_cast<uint8_t>(here[i] + above[i]);
  }
}

}  // namespace flagsim
