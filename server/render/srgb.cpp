#include "server/render/srgb.hpp"

#include <cmath>

namespace flagsim::render {

float SrgbToLinear(float s) {
  s = std::clamp(s, 0.0f, 1.0f);
  return s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f);
}

float LinearToSrgb(float linear) {
  linear = std::clamp(linear, 0.0f, 1.0f);
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

const std::array<uint32_t, kEncodeSteps> kSrgbEncode = [] {
  std::array<uint32_t, kEncodeSteps> table{};
  for (int k = 0; k < kEncodeSteps; ++k)
    table[size_t(k)] = uint32_t(std::lround(255.0 * LinearToSrgb(float(k) / float(kEncodeSteps - 1))));
  return table;
}();

const std::array<uint32_t, 256> kSrgbDecode = [] {
  std::array<uint32_t, 256> table{};
  for (int b = 0; b < 256; ++b)
    table[size_t(b)] = uint32_t(std::lround(double(kLinearOne) * SrgbToLinear(b / 255.0f)));
  return table;
}();

}  // namespace flagsim::render
