// A triangle drawn into a multisampled tile (sample_pattern.hpp), a row at a time:
//
//   coverage   per sample, the row's span of pixels whose sample is inside (RowSpans on the
//              grid moved by the sample's offset: exact, and shared edges cover each sample once)
//   depth      per sample, the triangle's depth plane at the sample, tested and written; a bit
//              per pixel and sample records where the triangle won
//   shading    once per pixel, at its centre, for the blocks of the row where any sample won
//   colour     stored to the samples that won
#pragma once

#include "server/render/tile_raster.hpp"
#include "server/render/triangle_setup.hpp"

namespace flagsim::render {

/// RasterizeTriangle for a target of more than one sample (context.samples' pattern).
void RasterizeMultisampled(const TriangleSetup& t, const ShadeContext& context, const TileTarget& target);

}  // namespace flagsim::render
