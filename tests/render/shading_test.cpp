#include "server/render/shading.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flagsim::render {
namespace {

/// One white sun towards `to_sun`, no ambient light.
Lighting Sun(const Eigen::Vector3f& to_sun) {
  Lighting lighting;
  lighting.ambient = Eigen::Vector3f::Zero();
  Light sun;
  sun.vector = to_sun.normalized();
  lighting.lights = {sun};
  return lighting;
}

const Eigen::Vector3f kUp(0, 1, 0);

TEST(Shading, PlainMaterialsAreBlinnPhong) {
  // Sun at 60 degrees from the normal, eye straight above: D = kd cos 60, S = ks (n . h)^p.
  Material material;
  const Lighting lighting = Sun(Eigen::Vector3f(std::sin(M_PI / 3), std::cos(M_PI / 3), 0));
  const Shade shade = ShadePoint(material, lighting, Eigen::Vector3f::Zero(), kUp, Eigen::Vector3f(0, 5, 0));
  EXPECT_NEAR(shade.diffuse.x(), material.diffuse * 0.5f, 1e-6f);
  const float n_dot_h = std::cos(float(M_PI) / 6);  // h halfway between the sun and the eye
  EXPECT_NEAR(shade.specular.x(), material.specular * std::pow(n_dot_h, material.shininess), 1e-6f);
}

TEST(Shading, WrappedLightReachesPastTheTerminator) {
  Material cloth;
  cloth.specular = 0;
  cloth.wrap = 0.5f;
  const Eigen::Vector3f eye(0, 5, 0);
  // The sun on the horizon (n . l = 0): a plain material is dark, a wrapped one gets kd w / (1 + w).
  const Shade at_terminator =
      ShadePoint(cloth, Sun(Eigen::Vector3f(1, 0, 0)), Eigen::Vector3f::Zero(), kUp, eye);
  EXPECT_NEAR(at_terminator.diffuse.x(), cloth.diffuse * 0.5f / 1.5f, 1e-6f);
  // n . l = -w: no light at all; overhead (n . l = 1): all of kd, as without wrap.
  const Eigen::Vector3f below(std::sqrt(0.75f), -0.5f, 0);
  EXPECT_EQ(ShadePoint(cloth, Sun(below), Eigen::Vector3f::Zero(), kUp, eye).diffuse.x(), 0.0f);
  EXPECT_NEAR(ShadePoint(cloth, Sun(kUp), Eigen::Vector3f::Zero(), kUp, eye).diffuse.x(), cloth.diffuse,
              1e-6f);
}

TEST(Shading, SheenBrightensTheClothSeenEdgeOn) {
  Material cloth;
  cloth.specular = 0;
  cloth.sheen = 0.4f;
  const Lighting lighting = Sun(kUp);  // overhead: lambert 1
  const Eigen::Vector3f p = Eigen::Vector3f::Zero();
  const Shade face_on = ShadePoint(cloth, lighting, p, kUp, Eigen::Vector3f(0, 5, 0));
  const Shade edge_on = ShadePoint(cloth, lighting, p, kUp, Eigen::Vector3f(5, 0, 0));
  const Shade at_60 =
      ShadePoint(cloth, lighting, p, kUp, Eigen::Vector3f(std::sin(M_PI / 3), std::cos(M_PI / 3), 0));
  EXPECT_NEAR(face_on.specular.x(), 0.0f, 1e-6f);
  EXPECT_NEAR(edge_on.specular.x(), cloth.sheen, 1e-6f);
  EXPECT_NEAR(at_60.specular.x(), cloth.sheen * std::pow(0.5f, 5.0f), 1e-6f);
}

}  // namespace
}  // namespace flagsim::render
