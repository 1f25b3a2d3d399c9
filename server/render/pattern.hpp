// The flag's pattern: an RGB8 texture made from a design, with an alpha channel where the design
// has transparent parts (a person's image: transparent pixels cut the flag's outline). The tiles sample it
// filtered (texture_filter.hpp); Sample here picks the nearest texel (a wireframe line's colour). (u, v) in
// [0, 1]^2: u runs along the flag from the hoist, v down from the top edge.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace flagsim::render {

struct Texture {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  ///< row-major, top row (v = 0) first; sRGB
  std::vector<uint8_t>
      alpha;  ///< a byte per texel, the same order, straight (not premultiplied); empty: opaque

  /// The texel under (u, v), clamped to the edges.
  const uint8_t* Sample(float u, float v) const { return &rgb[Texel(u, v) * 3]; }
  /// Its opacity, 0 .. 1 (1 without alpha).
  float Opacity(float u, float v) const { return alpha.empty() ? 1.0f : float(alpha[Texel(u, v)]) / 255.0f; }

 private:
  size_t Texel(float u, float v) const {
    int x = static_cast<int>(u * width), y = static_cast<int>(v * height);
    x = x < 0 ? 0 : x >= width ? width - 1 : x;
    y = y < 0 ? 0 : y >= height ? height - 1 : y;
    return size_t(y) * width + x;
  }
};

enum class FlagDesign {
  kNordicCross,  ///< an off-centre cross on a plain field
  kTricolour,    ///< three vertical bands
  kChecker,      ///< 8 x 8 squares: shows the mesh's parametrisation
  kImage,        ///< a person's own image (server/scene/design_file.hpp), not drawn here
};

/// Width over height of the built-in designs, as drawn.
constexpr double kBuiltInDesignAspect = 1.5;

/// The designs' names, in the enum's order (the `design` parameter's choices).
inline const std::vector<std::string>& FlagDesignNames() {
  static const std::vector<std::string> names = {"nordic_cross", "tricolour", "checker", "image"};
  return names;
}

/// The built-in design drawn into a width x height texture (kImage: a white one).
Texture MakePattern(FlagDesign design, int width, int height);

}  // namespace flagsim::render
