// The shadow the flag, the pole and the finial cast on the ground in the sun: a shadow map for
// a receiver that is the plane y = 0, below everything that casts.
//
// With the sun in direction l (towards it, l_y > 0), a point p falls on the ground at
//   p - (p_y / l_y) l
// and everything above the ground is nearer the sun than the ground under it, so the map needs
// no depth: a ground point is in shadow where any caster covers it. Each frame the casting
// meshes' triangles are projected so and drawn, a sample at each texel centre, into a square
// map of the ground around them (kTexels across, plus a margin), then box-filtered over 3 x 3
// texels; the ground samples it bilinearly at its (x, z). So the shadow's edge is smooth at any
// distance, and softer by about a texel (a few cm here), as the sun's half a degree would make
// it anyway.
//
// The ground shades in shadow without the sun's diffuse light and highlights:
//   colour = base * (D - s Dsun) + S (1 - s),   s the map's value, Dsun = kd (n . l) sun
// (the ground is flat, so Dsun is one colour per material).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "server/render/mesh.hpp"

namespace flagsim::render {

class GroundShadow {
 public:
  static constexpr int kTexels = 256;  ///< across the map

  /// The map of the meshes that cast, in the scene's light `scene.shadow_light`; no shadow when
  /// there is none, it is below the horizon, or nothing casts. A patterned mesh whose pattern has
  /// transparent texels casts the shadow of what is left of it.
  void Cast(const RenderScene& scene);

  /// 0 (in the sun) .. 1 (in full shadow) at ground point (x, z), m; 0 outside the map (its
  /// border texels are in the sun, and beyond it the nearest border texel is read) and with no
  /// map. Inline: the tiles call it per pixel.
  float At(float x, float z) const;

  /// Whether any ground point of the box [x0, x1] x [z0, z1] (m) may be in shadow.
  bool Touches(float x0, float z0, float x1, float z1) const;

  /// The sun's diffuse light on the flat ground for `material`: Dsun above.
  Eigen::Vector3f SunDiffuse(const Material& material) const;

  bool empty() const { return texels_.empty(); }

 private:
  /// One projected triangle's texels, each as dark as `opacity` (a function of the texel
  /// centre's barycentric weights, 0 .. 1) says: the pattern's alpha for a cut surface.
  template <class Opacity>
  void Draw(const Eigen::Vector2f& a, const Eigen::Vector2f& b, const Eigen::Vector2f& c,
            const Opacity& opacity);
  void Blur();

  Eigen::Vector2f origin_ = Eigen::Vector2f::Zero();     ///< m, the map's (x, z) corner
  float texel_size_ = 1;                                 ///< m
  float per_metre_ = 1;                                  ///< texels
  Eigen::Vector3f sun_light_ = Eigen::Vector3f::Zero();  ///< the casting light's colour times n . l
  std::vector<float> texels_, scratch_;                  ///< kTexels^2, row z, column x
};

inline float GroundShadow::At(float x, float z) const {
  if (texels_.empty()) return 0;
  constexpr float kLast = float(kTexels - 1);
  const float tx = std::clamp((x - origin_.x()) * per_metre_ - 0.5f, 0.0f, kLast);
  const float tz = std::clamp((z - origin_.y()) * per_metre_ - 0.5f, 0.0f, kLast);
  const int i = std::min(int(tx), kTexels - 2), j = std::min(int(tz), kTexels - 2);
  const float wx = tx - float(i), wz = tz - float(j);
  const float* row = texels_.data() + size_t(j) * kTexels + i;
  const float top = row[0] + (row[1] - row[0]) * wx;
  const float bottom = row[kTexels] + (row[kTexels + 1] - row[kTexels]) * wx;
  return top + (bottom - top) * wz;
}

}  // namespace flagsim::render
