#include "client/image_fit.hpp"

#include <algorithm>
#include <cmath>

namespace flagsim {
namespace {

/// Where a destination pixel's centre falls on the source's axis of `size` pixels, for a
/// scale of `scale` source pixels per destination pixel: the two pixels around it and the
/// weight of the second.
struct Sample {
  int low, high;
  double weight;
};

Sample SampleAt(int destination, double scale, int size) {
  const double source = std::clamp((destination + 0.5) * scale - 0.5, 0.0, double(size - 1));
  const int low = static_cast<int>(std::floor(source));
  return {low, std::min(low + 1, size - 1), source - low};
}

}  // namespace

// rgb, size => the fitted box (scale, offset) => each box pixel from its four neighbours
std::vector<uint8_t> FitImage(const uint8_t* rgb, int width, int height, int to_width, int to_height) {
  std::vector<uint8_t> fitted(size_t(to_width) * to_height * 3, 0);
  const double scale = std::min(double(to_width) / width, double(to_height) / height);
  const int box_width = std::clamp(int(std::lround(width * scale)), 1, to_width);
  const int box_height = std::clamp(int(std::lround(height * scale)), 1, to_height);
  const int left = (to_width - box_width) / 2, top = (to_height - box_height) / 2;
  for (int y = 0; y < box_height; ++y) {
    const Sample row = SampleAt(y, double(height) / box_height, height);
    for (int x = 0; x < box_width; ++x) {
      const Sample column = SampleAt(x, double(width) / box_width, width);
      uint8_t* out = &fitted[(size_t(top + y) * to_width + left + x) * 3];
      for (int c = 0; c < 3; ++c) {
        const auto at = [&](int yy, int xx) { return double(rgb[(size_t(yy) * width + xx) * 3 + c]); };
        const double upper =
            at(row.low, column.low) * (1 - column.weight) + at(row.low, column.high) * column.weight;
        const double lower =
            at(row.high, column.low) * (1 - column.weight) + at(row.high, column.high) * column.weight;
        out[c] = static_cast<uint8_t>(std::lround(upper * (1 - row.weight) + lower * row.weight));
      }
    }
  }
  return fitted;
}

}  // namespace flagsim
