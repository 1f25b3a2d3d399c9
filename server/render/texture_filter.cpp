#include "server/render/texture_filter.hpp"

#include <algorithm>
#include <cmath>

namespace flagsim::render {
namespace {

uint64_t Pack(uint64_t r, uint64_t g, uint64_t b, uint64_t alpha) {
  return r | g << 16 | b << 32 | alpha << 48;
}
uint64_t Channel(uint64_t texel, int k) { return texel >> (16 * k) & 0xffff; }

/// Level k + 1 from level k: each texel the rounded mean of a 2 x 2 block (of light, and alpha).
FilteredTexture::Level HalfOf(const FilteredTexture::Level& level) {
  FilteredTexture::Level half;
  half.width = std::max(1, level.width / 2);
  half.height = std::max(1, level.height / 2);
  half.texels.resize(size_t(half.width) * half.height);
  const auto at = [&level](int x, int y) {
    return level.texels[size_t(std::min(y, level.height - 1)) * level.width + std::min(x, level.width - 1)];
  };
  for (int y = 0; y < half.height; ++y) {
    for (int x = 0; x < half.width; ++x) {
      const uint64_t block[4] = {at(2 * x, 2 * y), at(2 * x + 1, 2 * y), at(2 * x, 2 * y + 1),
                                 at(2 * x + 1, 2 * y + 1)};
      uint64_t mean[4];
      for (int k = 0; k < 4; ++k) {
        mean[k] =
            (Channel(block[0], k) + Channel(block[1], k) + Channel(block[2], k) + Channel(block[3], k) + 2) /
            4;
      }
      half.texels[size_t(y) * half.width + x] = Pack(mean[0], mean[1], mean[2], mean[3]);
    }
  }
  return half;
}

}  // namespace

void FilteredTexture::Assign(const Texture& texture) {
  if (texture.width == source_width_ && texture.height == source_height_ && texture.rgb == source_ &&
      texture.alpha == source_alpha_)
    return;
  source_ = texture.rgb;
  source_alpha_ = texture.alpha;
  has_alpha_ = std::any_of(texture.alpha.begin(), texture.alpha.end(), [](uint8_t a) { return a < 255; });
  source_width_ = texture.width;
  source_height_ = texture.height;
  levels_.clear();
  if (texture.width <= 0 || texture.height <= 0) return;
  Level base;
  base.width = texture.width;
  base.height = texture.height;
  base.texels.resize(size_t(base.width) * base.height);
  for (size_t i = 0; i < base.texels.size(); ++i) {
    const uint64_t alpha = texture.alpha.empty() ? 255 : texture.alpha[i];
    const auto premultiplied = [alpha](uint8_t byte) { return (kSrgbDecode[byte] * alpha + 127) / 255; };
    base.texels[i] = Pack(premultiplied(texture.rgb[3 * i]), premultiplied(texture.rgb[3 * i + 1]),
                          premultiplied(texture.rgb[3 * i + 2]), kLinearOne * alpha / 255);
  }
  levels_.push_back(std::move(base));
  while (levels_.back().width > 1 || levels_.back().height > 1) levels_.push_back(HalfOf(levels_.back()));
}

float FilteredTexture::LevelOfDetail(float uv_area_per_pixel) const {
  if (levels_.empty()) return 0;
  const float texels_per_pixel = uv_area_per_pixel * float(levels_[0].width) * float(levels_[0].height);
  if (!(texels_per_pixel > 1)) return 0;  // magnified (or degenerate): the full-size level
  return std::min(0.5f * std::log2(texels_per_pixel), float(levels_.size() - 1));
}

}  // namespace flagsim::render
