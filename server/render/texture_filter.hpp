// The flag's pattern as the tiles sample it: trilinear filtering (bilinear within a level of a
// mipmap chain, blended between the two levels around the level of detail), so that the
// pattern's edges are smooth up close and do not shimmer as the cloth folds away.
//
//   level 0     the texture; level k + 1: each texel the mean of a 2 x 2 block of level k (a
//               level of odd size repeats its last row or column), down to 1 x 1
//   level of    lod = log2(rho), rho = texels per pixel along the surface; per triangle:
//   detail      rho^2 = (the triangle's area in texels) / (its area in pixels)
//   bilinear    texel centres at ((i + 1/2) / width, (j + 1/2) / height), clamped at the edges
//
// The texture's sRGB bytes are decoded once, to 16-bit linear light (srgb.hpp): levels are means
// of light and filtering blends light, as a GPU does with an sRGB texture. A texel is one 64-bit
// word: R, G, B and alpha in 16 bits each, 0 .. kLinearOne, the colour premultiplied by alpha
// so that transparent texels lend no colour to their neighbours (an opaque texture's colour is
// as it was, its alpha kLinearOne everywhere). A texture with transparent texels is sampled for
// its straight colour and its alpha (SampleStraight), which cut the flag's outline.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "server/render/pattern.hpp"
#include "server/render/srgb.hpp"

namespace flagsim::render {

class FilteredTexture {
 public:
  struct Level {
    int width = 0, height = 0;
    std::vector<uint64_t> texels;  ///< row-major, top row first; 16-bit linear R, G, B (premultiplied), alpha
  };

  /// The levels of `texture`; nothing to do if they are from the same bytes already.
  void Assign(const Texture& texture);

  /// The level of detail for a triangle covering `uv_area_per_pixel` of (u, v) per px²: 0 where a
  /// texel covers a pixel or more (magnified), up to the last level.
  float LevelOfDetail(float uv_area_per_pixel) const;

  /// The two levels around level of detail `lod` (LevelOfDetail's) and how far it is from the
  /// first to the second: what every pixel of one triangle samples.
  struct Sampler {
    const Level* first = nullptr;
    const Level* second = nullptr;  ///< the same level where there is no next one
    float blend = 0;
    /// The filtered colour at (u, v), each channel 0..1 of linear light (premultiplied by alpha,
    /// where the texture has any). Inline and branch-free: the tiles call it per pixel in loops
    /// the compiler vectorises.
    void Sample(float u, float v, float rgb[3]) const;
    /// The filtered colour, straight (divided by alpha; 0 where alpha is 0), and alpha 0..1.
    void SampleStraight(float u, float v, float rgb[3], float* alpha) const;
  };
  /// The sampler for `lod`; the texture must have levels (Assign a texture of some size first).
  Sampler SamplerAt(float lod) const;

  /// The filtered colour at (u, v) and level of detail `lod`, each channel 0..1 of linear light
  /// (white when the texture is empty).
  void Sample(float u, float v, float lod, float rgb[3]) const;

  const std::vector<Level>& levels() const { return levels_; }
  /// Whether any texel is less than opaque: the flag's outline is cut where alpha is low.
  bool has_alpha() const { return has_alpha_; }

 private:
  std::vector<Level> levels_;
  std::vector<uint8_t> source_;        ///< the RGB bytes level 0 is from
  std::vector<uint8_t> source_alpha_;  ///< and the alpha bytes
  bool has_alpha_ = false;
  int source_width_ = 0, source_height_ = 0;
};

/// Bilinear within `level` at (u, v), the first kChannels channels (R, G, B, alpha) 0..kLinearOne.
template <int kChannels = 3>
inline void SampleBilinear(const FilteredTexture::Level& level, float u, float v, float rgb[kChannels]) {
  const float x = u * float(level.width) - 0.5f, y = v * float(level.height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  const int x0 = std::clamp(int(fx), 0, level.width - 1), x1 = std::clamp(int(fx) + 1, 0, level.width - 1);
  const int y0 = std::clamp(int(fy), 0, level.height - 1), y1 = std::clamp(int(fy) + 1, 0, level.height - 1);
  const uint64_t* row0 = &level.texels[size_t(y0) * level.width];
  const uint64_t* row1 = &level.texels[size_t(y1) * level.width];
  const uint64_t a = row0[x0], b = row0[x1], c = row1[x0], d = row1[x1];
  for (int k = 0; k < kChannels; ++k) {
    const float ta = float(a >> (16 * k) & 0xffff), tb = float(b >> (16 * k) & 0xffff);
    const float tc = float(c >> (16 * k) & 0xffff), td = float(d >> (16 * k) & 0xffff);
    const float top = ta + (tb - ta) * tx, bottom = tc + (td - tc) * tx;
    rgb[k] = top + (bottom - top) * ty;
  }
}

inline void FilteredTexture::Sampler::Sample(float u, float v, float rgb[3]) const {
  float next[3];
  SampleBilinear(*first, u, v, rgb);
  SampleBilinear(*second, u, v, next);
  for (int k = 0; k < 3; ++k) rgb[k] = (rgb[k] + (next[k] - rgb[k]) * blend) * (1.0f / float(kLinearOne));
}

inline void FilteredTexture::Sampler::SampleStraight(float u, float v, float rgb[3], float* alpha) const {
  float here[4], next[4];
  SampleBilinear<4>(*first, u, v, here);
  SampleBilinear<4>(*second, u, v, next);
  float blended[4];
  for (int k = 0; k < 4; ++k) blended[k] = here[k] + (next[k] - here[k]) * blend;
  const float over = blended[3] > 0 ? 1.0f / blended[3] : 0.0f;  // premultiplied => straight
  for (int k = 0; k < 3; ++k) rgb[k] = blended[k] * over;
  *alpha = blended[3] * (1.0f / float(kLinearOne));
}

inline FilteredTexture::Sampler FilteredTexture::SamplerAt(float lod) const {
  const int last = int(levels_.size()) - 1;
  const int level = std::clamp(int(lod), 0, last);
  return {&levels_[size_t(level)], &levels_[size_t(std::min(level + 1, last))],
          level < last ? lod - float(level) : 0.0f};
}

inline void FilteredTexture::Sample(float u, float v, float lod, float rgb[3]) const {
  if (levels_.empty()) {
    rgb[0] = rgb[1] = rgb[2] = 1;
    return;
  }
  SamplerAt(lod).Sample(u, v, rgb);
}

}  // namespace flagsim::render
