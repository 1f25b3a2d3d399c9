#include "server/render/sample_pattern.hpp"

#include <algorithm>
#include <cstdlib>
#include <initializer_list>

namespace flagsim::render {
namespace {

/// Offsets given in 1/16 px.
SamplePattern Sixteenths(std::initializer_list<SampleOffset> offsets) {
  static_assert(kSubpixels % 16 == 0);
  SamplePattern pattern;
  pattern.count = 0;
  for (const SampleOffset& o : offsets) {
    const SampleOffset in_subpixels{o.x * int(kSubpixels / 16), o.y * int(kSubpixels / 16)};
    pattern.offsets[pattern.count++] = in_subpixels;
    pattern.reach = std::max({pattern.reach, std::abs(in_subpixels.x), std::abs(in_subpixels.y)});
  }
  const int all = (1 << pattern.count) - 1;
  for (int mask = 1; mask < all; ++mask) {
    float x = 0, y = 0;
    int bits = 0;
    for (int k = 0; k < pattern.count; ++k) {
      if (!(mask >> k & 1)) continue;
      x += float(pattern.offsets[k].x) / kSubpixels;
      y += float(pattern.offsets[k].y) / kSubpixels;
      ++bits;
    }
    pattern.centroid_x[mask] = x / bits;
    pattern.centroid_y[mask] = y / bits;
  }
  return pattern;
}

}  // namespace

SamplePattern PatternOf(Antialiasing mode) {
  switch (mode) {
    case Antialiasing::kOff:
      return SamplePattern{};
    case Antialiasing::kMsaa2:
      return Sixteenths({{4, 4}, {-4, -4}});
    case Antialiasing::kMsaa4:
      return Sixteenths({{-2, -6}, {6, -2}, {-6, 2}, {2, 6}});
    case Antialiasing::kMsaa8:
      return Sixteenths({{1, -3}, {-1, 3}, {5, 1}, {-3, -5}, {-5, 5}, {-7, -1}, {3, 7}, {7, -7}});
  }
  return SamplePattern{};
}

}  // namespace flagsim::render
