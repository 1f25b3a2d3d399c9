// Light is added and averaged in linear units; pictures and patterns are stored in sRGB, whose
// bytes are spaced as the eye sees (IEC 61966-2-1):
//
//   linear = s / 12.92                       s <= 0.04045
//            ((s + 0.055) / 1.055)^2.4       above
//   s      = 12.92 linear                    linear <= 0.0031308
//            1.055 linear^(1 / 2.4) - 0.055  above
//
// The renderer decodes the pattern's texels once, to 16-bit linear (texture_filter.hpp), lights
// and blends in linear, and encodes each pixel's colour (or its samples' mean) to an sRGB byte
// through a table of kEncodeSteps linear steps: fine enough that every byte comes back from its
// own linear value (near black an sRGB byte spans about 1.2 steps).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

namespace flagsim::render {

float SrgbToLinear(float s);  ///< 0..1 => 0..1
float LinearToSrgb(float linear);

constexpr int kEncodeSteps = 4096;      ///< linear 0 .. 1 in kEncodeSteps - 1 steps
constexpr uint32_t kLinearOne = 65520;  ///< 16-bit linear 1: (kEncodeSteps - 1) * 16, so a
                                        ///< 16-bit value's step is value / 16, rounded

/// The sRGB byte of linear k / (kEncodeSteps - 1), for k = 0 .. kEncodeSteps - 1 (32-bit
/// entries: vector loops gather them).
extern const std::array<uint32_t, kEncodeSteps> kSrgbEncode;
/// Byte b's linear value times kLinearOne, rounded, for b = 0 .. 255.
extern const std::array<uint32_t, 256> kSrgbDecode;

/// Linear 0..1 (clamped) => sRGB byte. Inline and branch-free: the tiles call it per pixel in
/// loops the compiler vectorises.
inline uint32_t EncodeSrgb(float linear) {
  const int step =
      static_cast<int>(std::min(linear * float(kEncodeSteps - 1) + 0.5f, float(kEncodeSteps - 1)));
  return kSrgbEncode[size_t(std::max(step, 0))];
}

/// 16-bit linear (0 .. kLinearOne) => sRGB byte.
inline uint32_t EncodeSrgb16(uint32_t linear) {
  return kSrgbEncode[std::min((linear + 8) >> 4, uint32_t(kEncodeSteps - 1))];
}

}  // namespace flagsim::render
