#include "server/render/shading.hpp"

#include <algorithm>
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
    const float lambert = (n.dot(to_light) + material.wrap) / (1.0f + material.wrap);
    if (lambert <= 0) continue;
    shade.diffuse += material.diffuse * lambert * light.colour;
    if (!light.specular) continue;
    const float highlight = n.dot((to_light + to_eye).normalized());
    if (highlight > 0)
      shade.specular += material.specular * std::pow(highlight, material.shininess) * light.colour;
    if (material.sheen > 0) {
      const float edge_on = 1.0f - std::max(0.0f, n.dot(to_eye));
      const float edge_on2 = edge_on * edge_on;
      shade.specular += material.sheen * edge_on2 * edge_on2 * edge_on * lambert * light.colour;
    }
  }
  return shade;
}

}  // namespace flagsim::render
