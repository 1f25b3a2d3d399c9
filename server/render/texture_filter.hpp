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
// Texels are RGBX words (bytes R, G, B, 0), as the tiles store pixels.
#pragma once

#include <cstdint>
#include <vector>

#include "server/render/pattern.hpp"

namespace flagsim::render {

class FilteredTexture {
 public:
  struct Level {
    int width = 0, height = 0;
    std::vector<uint32_t> texels;  ///< row-major, top row first
  };

  /// The levels of `texture`; nothing to do if they are from the same bytes already.
  void Assign(const Texture& texture);

  /// The level of detail for a triangle covering `uv_area_per_pixel` of (u, v) per px²: 0 where a
  /// texel covers a pixel or more (magnified), up to the last level.
  float LevelOfDetail(float uv_area_per_pixel) const;

  /// The filtered colour at (u, v) and level of detail `lod` (LevelOfDetail's), each channel 0..1.
  void Sample(float u, float v, float lod, float rgb[3]) const;

  const std::vector<Level>& levels() const { return levels_; }

 private:
  std::vector<Level> levels_;
  std::vector<uint8_t> source_;  ///< the RGB bytes level 0 is from
  int source_width_ = 0, source_height_ = 0;
};

/// Bilinear within `level` at (u, v), each channel 0..255.
void SampleBilinear(const FilteredTexture::Level& level, float u, float v, float rgb[3]);

}  // namespace flagsim::render
