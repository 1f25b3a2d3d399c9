// Multisampling: where in each pixel coverage and depth are tested.
//
// With n samples a pixel keeps n colours and n depths. A triangle is tested at each sample
// (the same exact edge functions as at the pixel centre, on a grid shifted by the sample's
// offset), the depth test runs per sample, and the pixel is shaded once for all the samples
// the triangle wins, at the mean place of those samples (SamplePattern::centroid_x, _y). The
// picture is the mean of a pixel's samples, in light: an edge crossing a pixel leaves it the
// share of the samples each side covers.
//
// The offsets are the usual rotated grids (the standard 2x, 4x and 8x positions of Direct3D
// and Vulkan), in 1/16 px: no two samples share a row or a column, so a near-horizontal or
// near-vertical edge still gets n levels of coverage.
#pragma once

#include <string>
#include <vector>

#include "server/render/triangle_setup.hpp"

namespace flagsim::render {

enum class Antialiasing { kOff, kMsaa2, kMsaa4, kMsaa8 };

/// Names as PARAM and scene files spell them, in Antialiasing order.
inline const std::vector<std::string>& AntialiasingNames() {
  static const std::vector<std::string> names = {"off", "msaa2", "msaa4", "msaa8"};
  return names;
}

struct SamplePattern {
  int count = 1;
  SampleOffset offsets[kMaxSamples] = {};
  int reach = 0;  ///< subpixels: the largest |offset| in x or y, how far past the centre a sample lies
  /// px from the centre: the mean place of the samples whose bits are set in the index, where a
  /// pixel a triangle wins only in part is shaded (inside the triangle, where the centre may not
  /// be); the centre for all or none. Indexed by a mask of `count` bits.
  float centroid_x[1 << kMaxSamples] = {}, centroid_y[1 << kMaxSamples] = {};
};

/// The samples of `mode`: one at the centre when off.
SamplePattern PatternOf(Antialiasing mode);

}  // namespace flagsim::render
