// Materials, lights and the Blinn-Phong lighting model.
//
// At a point p with unit normal n seen from the eye e, with l the unit vector to a light and
// h = normalize(l + v), v = normalize(e - p):
//   diffuse  D = ambient * ka + sum_lights kd L * light,  L = max(0, (n . l + wrap) / (1 + wrap))
//   specular S = sum_lights (ks max(0, n . h)^shininess + sheen (1 - n . v)^5 L) * light
//                (0 where L = 0, and for lights that only diffuse: the light of the sky and
//                of the ground)
// and the colour is  base * D + S,  base being the material's colour, or its pattern's texel
// times that colour. With wrap = sheen = 0 this is OpenGL's lighting with a separate specular
// colour and a modulated texture, so a GL renderer can draw the same picture. Cloth is not
// metal: light wraps past the terminator a little as it scatters in the weave (wrap), its
// highlight is dim and broad, and it brightens where it is seen edge on, the fibres catching
// the light along the folds (sheen).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace flagsim::render {

struct Material {
  Eigen::Vector3f colour{0.8f, 0.8f, 0.8f};  ///< linear RGB, 0..1; multiplies the pattern
  bool patterned = false;                    ///< the flag's pattern (texture) applies
  float ambient = 0.25f;                     ///< ka
  float diffuse = 0.8f;                      ///< kd
  float specular = 0.2f;                     ///< ks
  float shininess = 24.0f;                   ///< Blinn-Phong exponent
  float wrap = 0.0f;                         ///< 0..1: how far past the terminator diffuse light reaches
  float sheen = 0.0f;                        ///< the rim's brightness seen edge on, lit side
  /// Shadowed by the meshes that cast (ground_shadow.hpp): the ground only, whose (u, v) are
  /// its (x, z) in metres.
  bool receives_shadow = false;
};

struct Light {
  enum Kind { kDirectional, kPoint };
  Kind kind = kDirectional;
  Eigen::Vector3f vector{0, 1, 0};  ///< directional: towards the light; point: position, m
  Eigen::Vector3f colour{1, 1, 1};  ///< linear RGB intensity
  bool specular = true;             ///< it makes highlights (the sun); false: it only diffuses (sky, ground)
};

struct Lighting {
  Eigen::Vector3f ambient{0.35f, 0.38f, 0.45f};  ///< linear RGB, the sky's light
  std::vector<Light> lights;
};

/// Diffuse and specular light at one point, before the base colour.
struct Shade {
  Eigen::Vector3f diffuse = Eigen::Vector3f::Zero();
  Eigen::Vector3f specular = Eigen::Vector3f::Zero();
};

/// Blinn-Phong at p with unit normal n, eye at `eye` (all world frame).
Shade ShadePoint(const Material& material, const Lighting& lighting, const Eigen::Vector3f& p,
                 const Eigen::Vector3f& n, const Eigen::Vector3f& eye);

}  // namespace flagsim::render
