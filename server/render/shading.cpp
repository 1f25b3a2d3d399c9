#include "server/render/shading.hpp"

#include <cmath>

namespace flagsim::render {

Shade ShadePoint(const Material& material, const Lighting& lighting, const Eigen::Vector3f& p,
                 const Eigen::Vector3f& n, const Eigen::Vector3f& eye) {
  Shade shade;
  shade.diffuse = material.ambient * lighting.ambient;
  const Eigen::Vector3f to_eye = (eye - p).normalized();
  for (const Light& light : lighting.lights) {
    const Eigen::Vector3f to_light =
        light.kind == Light::kDirectional ? light.vector.normalized() : (light.vector - p).normalized();
    const float lambert = n.dot(to_light);
    if (lambert <= 0) continue;
    shade.diffuse += material.diffuse * lambert * light.colour;
    if (!light.specular) continue;
    const float highlight = n.dot((to_light + to_eye).normalized());
    if (highlight > 0)
      shade.specular += material.specular * std::pow(highlight, material.shininess) * light.colour;
  }
  return shade;
}

}  // namespace flagsim::render
