// What the benchmarks measure, the same way in each: the median time of a repeated draw, and
// the peak signal-to-noise ratio between two RGB8 images.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include "server/render/srgb.hpp"

namespace flagsim::bench {

/// draw() `warmup` times untimed, then `frames` times timed => median ms per call.
template <typename Draw>
double MedianMs(int warmup, int frames, Draw draw) {
  for (int i = 0; i < warmup; ++i) draw();
  std::vector<double> times;
  for (int i = 0; i < frames; ++i) {
    const auto start = std::chrono::steady_clock::now();
    draw();
    const auto end = std::chrono::steady_clock::now();
    times.push_back(std::chrono::duration<double, std::milli>(end - start).count());
  }
  std::sort(times.begin(), times.end());
  const size_t middle = times.size() / 2;
  return times.size() % 2 == 1 ? times[middle] : 0.5 * (times[middle - 1] + times[middle]);
}

/// An sRGB8 image `large_width` px wide => one `factor` times smaller each way, each factor x
/// factor block of samples averaged per channel in light (decoded, averaged, encoded: as the
/// renderer resolves its samples), a supersampled reference.
inline std::vector<uint8_t> BoxFilter(const std::vector<uint8_t>& large, int large_width, int factor) {
  const int width = large_width / factor, height = int(large.size() / 3 / size_t(large_width)) / factor;
  const int samples = factor * factor;
  std::vector<uint8_t> small(size_t(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      uint32_t sums[3] = {0, 0, 0};
      for (int sy = 0; sy < factor; ++sy) {
        for (int sx = 0; sx < factor; ++sx) {
          const uint8_t* sample = &large[(size_t(y * factor + sy) * large_width + size_t(x * factor + sx)) * 3];
          for (int k = 0; k < 3; ++k) sums[k] += render::kSrgbDecode[sample[k]];
        }
      }
      for (int k = 0; k < 3; ++k) {
        small[(size_t(y) * width + x) * 3 + k] = uint8_t(render::EncodeSrgb16((sums[k] + samples / 2) / samples));
      }
    }
  }
  return small;
}

/// Two RGB8 images, and a per-pixel mask or none => PSNR over the (masked) pixels' channels, dB
/// (peak 255); infinite when they agree.
inline double Psnr(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b,
                   const std::vector<uint8_t>* mask = nullptr) {
  double squares = 0;
  size_t values = 0;
  for (size_t pixel = 0; pixel * 3 < a.size(); ++pixel) {
    if (mask && !(*mask)[pixel]) continue;
    for (size_t k = pixel * 3; k < pixel * 3 + 3; ++k) {
      const double difference = double(a[k]) - double(b[k]);
      squares += difference * difference;
    }
    values += 3;
  }
  if (squares == 0) return INFINITY;
  return 10.0 * std::log10(255.0 * 255.0 / (squares / double(values)));
}

}  // namespace flagsim::bench
