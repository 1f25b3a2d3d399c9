#include "server/render/ground_shadow.hpp"

#include <algorithm>
#include <cmath>

namespace flagsim::render {
namespace {

constexpr float kMargin = 0.25f;  ///< m of ground around the casters' shadow on each side

}  // namespace

void GroundShadow::Cast(const RenderScene& scene) {
  texels_.clear();
  if (scene.shadow_light < 0) return;
  const Light& sun = scene.lighting.lights[size_t(scene.shadow_light)];
  const Eigen::Vector3f l = sun.vector.normalized();
  if (sun.kind != Light::kDirectional || l.y() <= 0.05f) return;  // no sun, or it is setting: no shadow
  sun_light_ = l.y() * sun.colour;
  // Every casting vertex on the ground, and their box.
  const auto on_ground = [&](const Eigen::Vector3f& p) {
    const Eigen::Vector3f q = p - (p.y() / l.y()) * l;
    return Eigen::Vector2f(q.x(), q.z());
  };
  Eigen::Vector2f low(INFINITY, INFINITY), high(-INFINITY, -INFINITY);
  for (const Mesh& mesh : scene.meshes) {
    if (!mesh.casts_shadow) continue;
    for (const Eigen::Vector3f& p : mesh.positions) {
      low = low.cwiseMin(on_ground(p));
      high = high.cwiseMax(on_ground(p));
    }
  }
  if (!(low.x() <= high.x())) return;  // nothing casts
  const float size = std::max(high.x() - low.x(), high.y() - low.y()) + 2 * kMargin;
  texel_size_ = size / kTexels;
  per_metre_ = kTexels / size;
  origin_ = low - Eigen::Vector2f::Constant(kMargin);
  texels_.assign(size_t(kTexels) * kTexels, 0.0f);
  for (const Mesh& mesh : scene.meshes) {
    if (!mesh.casts_shadow) continue;
    const bool cut = scene.materials[size_t(mesh.front_material)].patterned && !scene.pattern.alpha.empty() &&
                     mesh.uvs.size() == mesh.positions.size();
    for (const auto& triangle : mesh.triangles) {
      const Eigen::Vector2f a = (on_ground(mesh.positions[triangle[0]]) - origin_) / texel_size_;
      const Eigen::Vector2f b = (on_ground(mesh.positions[triangle[1]]) - origin_) / texel_size_;
      const Eigen::Vector2f c = (on_ground(mesh.positions[triangle[2]]) - origin_) / texel_size_;
      if (!cut) {
        Draw(a, b, c, [](const Eigen::Vector3f&) { return 1.0f; });
        continue;
      }
      const Eigen::Vector2f& ua = mesh.uvs[triangle[0]];
      const Eigen::Vector2f& ub = mesh.uvs[triangle[1]];
      const Eigen::Vector2f& uc = mesh.uvs[triangle[2]];
      Draw(a, b, c, [&](const Eigen::Vector3f& weight) {
        const Eigen::Vector2f uv = weight[0] * ua + weight[1] * ub + weight[2] * uc;
        return scene.pattern.Opacity(uv.x(), uv.y());
      });
    }
  }
  Blur();
}

// One projected triangle (in texels) covers the texels whose centres are inside it, on either
// winding (the sun sees the cloth from both sides): row by row, the span between where the
// row's centre line crosses its edges.
template <class Opacity>
void GroundShadow::Draw(const Eigen::Vector2f& a, const Eigen::Vector2f& b, const Eigen::Vector2f& c,
                        const Opacity& opacity) {
  const Eigen::Vector2f* corners[3] = {&a, &b, &c};
  // Barycentric weights of point p: the areas opposite each corner over the whole (signed).
  const auto cross = [](const Eigen::Vector2f& u, const Eigen::Vector2f& v) {
    return u.x() * v.y() - u.y() * v.x();
  };
  const float area = cross(b - a, c - a);
  if (area == 0) return;
  const float low = std::min({a.y(), b.y(), c.y()}), high = std::max({a.y(), b.y(), c.y()});
  const int first_row = std::max(0, int(std::ceil(low - 0.5f))),
            last_row = std::min(kTexels - 1, int(std::floor(high - 0.5f)));
  for (int y = first_row; y <= last_row; ++y) {
    const float centre = float(y) + 0.5f;
    float left = INFINITY, right = -INFINITY;
    for (int e = 0; e < 3; ++e) {
      const Eigen::Vector2f& p = *corners[e];
      const Eigen::Vector2f& q = *corners[(e + 1) % 3];
      if ((centre < p.y()) == (centre < q.y())) continue;  // the row does not cross this edge
      const float x = p.x() + (centre - p.y()) * (q.x() - p.x()) / (q.y() - p.y());
      left = std::min(left, x);
      right = std::max(right, x);
    }
    if (left > right) continue;  // the line only touches a corner (the top one): no centre inside
    const int first = std::max(0, int(std::ceil(left - 0.5f))),
              last = std::min(kTexels - 1, int(std::floor(right - 0.5f)));
    float* row = &texels_[size_t(y) * kTexels];
    for (int x = first; x <= last; ++x) {
      const Eigen::Vector2f p(float(x) + 0.5f, centre);
      const Eigen::Vector3f weight(cross(b - p, c - p) / area, cross(c - p, a - p) / area,
                                   cross(a - p, b - p) / area);
      row[x] = std::max(row[x], opacity(weight));
    }
  }
}

// 3 x 3 box, as a 3-tap pass along x and then along z (edges repeat the last texel).
void GroundShadow::Blur() {
  scratch_.resize(texels_.size());
  const auto pass = [](const std::vector<float>& in, std::vector<float>* out, int step_x, int step_y) {
    for (int y = 0; y < kTexels; ++y) {
      for (int x = 0; x < kTexels; ++x) {
        float sum = 0;
        for (int d = -1; d <= 1; ++d) {
          const int sx = std::clamp(x + d * step_x, 0, kTexels - 1),
                    sy = std::clamp(y + d * step_y, 0, kTexels - 1);
          sum += in[size_t(sy) * kTexels + sx];
        }
        (*out)[size_t(y) * kTexels + x] = sum / 3;
      }
    }
  };
  pass(texels_, &scratch_, 1, 0);
  pass(scratch_, &texels_, 0, 1);
}

bool GroundShadow::Touches(float x0, float z0, float x1, float z1) const {
  if (texels_.empty()) return false;
  const float size = texel_size_ * kTexels;
  return x1 >= origin_.x() && x0 <= origin_.x() + size && z1 >= origin_.y() && z0 <= origin_.y() + size;
}

Eigen::Vector3f GroundShadow::SunDiffuse(const Material& material) const {
  return material.diffuse * sun_light_;
}

}  // namespace flagsim::render
