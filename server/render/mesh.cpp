#include "server/render/mesh.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "server/render/srgb.hpp"

namespace flagsim::render {

constexpr int kPatternWidth = 960, kPatternHeight = 640;  ///< texels of the built-in designs
static_assert(kPatternWidth == kBuiltInDesignAspect * kPatternHeight);
namespace {

void BuildGridTopology(int cols, int rows, Mesh* mesh) {
  mesh->triangles.clear();
  mesh->edges.clear();
  mesh->uvs.resize(size_t(cols) * rows);
  const auto index = [cols](int r, int c) { return static_cast<uint32_t>(r * cols + c); };
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      mesh->uvs[index(r, c)] = Eigen::Vector2f(float(c) / (cols - 1), float(r) / (rows - 1));
      if (c + 1 < cols) mesh->edges.push_back({index(r, c), index(r, c + 1)});
      if (r + 1 < rows) mesh->edges.push_back({index(r, c), index(r + 1, c)});
      if (r + 1 < rows && c + 1 < cols) {
        // upper (r, c) (r+1, c) (r, c+1) and lower (r+1, c) (r+1, c+1) (r, c+1): normal +z at rest
        mesh->triangles.push_back({index(r, c), index(r + 1, c), index(r, c + 1)});
        mesh->triangles.push_back({index(r + 1, c), index(r + 1, c + 1), index(r, c + 1)});
        mesh->edges.push_back({index(r + 1, c), index(r, c + 1)});
      }
    }
  }
}

}  // namespace

void UpdateFlagMesh(int cols, int rows, const float* x, const float* y, const float* z, Mesh* mesh) {
  const size_t n = size_t(cols) * rows;
  if (mesh->uvs.size() != n || mesh->edges.empty()) BuildGridTopology(cols, rows, mesh);
  mesh->positions.resize(n);
  mesh->normals.resize(n);
  for (size_t i = 0; i < n; ++i) mesh->positions[i] = Eigen::Vector3f(x[i], y[i], z[i]);
  // n = (P(r, c+1) - P(r, c-1)) x (P(r-1, c) - P(r+1, c)), one-sided at the edges: +z at rest.
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const auto at = [&](int rr, int cc) -> const Eigen::Vector3f& {
        return mesh->positions[rr * cols + cc];
      };
      const Eigen::Vector3f along = at(r, c + 1 < cols ? c + 1 : c) - at(r, c > 0 ? c - 1 : c);
      const Eigen::Vector3f up = at(r > 0 ? r - 1 : r, c) - at(r + 1 < rows ? r + 1 : r, c);
      const Eigen::Vector3f normal = along.cross(up);
      const float length = normal.norm();
      mesh->normals[r * cols + c] = length > 0 ? Eigen::Vector3f(normal / length) : Eigen::Vector3f(0, 0, 1);
    }
  }
}

Mesh CylinderMesh(const Eigen::Vector3f& base, float radius, float height, int segments) {
  Mesh mesh;
  for (int i = 0; i <= segments; ++i) {
    const float angle = 2 * float(M_PI) * i / segments;
    const Eigen::Vector3f radial(std::sin(angle), 0, std::cos(angle));
    for (const float h : {0.0f, height}) {
      mesh.positions.push_back(base + radius * radial + Eigen::Vector3f(0, h, 0));
      mesh.normals.push_back(radial);
      mesh.uvs.emplace_back(float(i) / segments, h / height);
    }
  }
  for (uint32_t i = 0; i < uint32_t(segments); ++i) {
    const uint32_t bottom = 2 * i, top = bottom + 1, next_bottom = bottom + 2, next_top = bottom + 3;
    mesh.triangles.push_back({bottom, next_bottom, top});
    mesh.triangles.push_back({top, next_bottom, next_top});
    mesh.edges.push_back({bottom, top});
  }
  return mesh;
}

Mesh SphereMesh(const Eigen::Vector3f& centre, float radius, int segments) {
  Mesh mesh;
  const int stacks = segments / 2;
  for (int s = 0; s <= stacks; ++s) {
    const float polar = float(M_PI) * s / stacks;  // 0 at the top
    for (int i = 0; i <= segments; ++i) {
      const float azimuth = 2 * float(M_PI) * i / segments;
      const Eigen::Vector3f normal(std::sin(polar) * std::sin(azimuth), std::cos(polar),
                                   std::sin(polar) * std::cos(azimuth));
      mesh.positions.push_back(centre + radius * normal);
      mesh.normals.push_back(normal);
      mesh.uvs.emplace_back(float(i) / segments, float(s) / stacks);
    }
  }
  const uint32_t row = uint32_t(segments) + 1;
  for (uint32_t s = 0; s < uint32_t(stacks); ++s) {
    for (uint32_t i = 0; i < uint32_t(segments); ++i) {
      const uint32_t a = s * row + i, b = a + row;  // a above b
      if (s > 0) mesh.triangles.push_back({a, b, a + 1});
      if (s + 1 < uint32_t(stacks)) mesh.triangles.push_back({a + 1, b, b + 1});
      mesh.edges.push_back({a, b});
      if (s > 0) mesh.edges.push_back({a, a + 1});
    }
  }
  return mesh;
}

Mesh GroundMesh(float x, float z, float size) {
  Mesh mesh;
  const float h = size / 2;
  for (const auto& [dx, dz] : {std::pair{-h, -h}, std::pair{-h, h}, std::pair{h, h}, std::pair{h, -h}}) {
    mesh.positions.emplace_back(x + dx, 0.0f, z + dz);
    mesh.normals.emplace_back(0.0f, 1.0f, 0.0f);
    mesh.uvs.emplace_back(x + dx, z + dz);
  }
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};  // counter-clockwise seen from above
  mesh.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  return mesh;
}

namespace {

/// A colour as a picture shows it (sRGB, 0..1) => the linear reflectance the lighting takes.
Eigen::Vector3f FromSrgb(float r, float g, float b) {
  return Eigen::Vector3f(SrgbToLinear(r), SrgbToLinear(g), SrgbToLinear(b));
}

}  // namespace

RenderScene DefaultRenderScene(float pole_height, float pole_radius, FlagDesign design) {
  RenderScene scene;
  Material cloth_front;
  cloth_front.patterned = true;
  cloth_front.colour = Eigen::Vector3f(1, 1, 1);
  cloth_front.ambient = 0.35f;
  cloth_front.diffuse = 0.75f;
  cloth_front.specular = 0.05f;  // a dim, broad highlight: cloth, not metal
  cloth_front.shininess = 8;
  cloth_front.wrap = 0.3f;
  cloth_front.sheen = 0.1f;
  Material cloth_back = cloth_front;  // the same cloth seen through: a little duller
  cloth_back.diffuse = 0.65f;
  cloth_back.specular = 0.025f;
  Material metal;
  metal.colour = FromSrgb(0.72f, 0.73f, 0.76f);
  metal.ambient = 0.3f;
  metal.diffuse = 0.6f;
  metal.specular = 0.8f;
  metal.shininess = 60;
  Material gold = metal;
  gold.colour = FromSrgb(0.85f, 0.68f, 0.25f);
  Material grass;
  grass.colour = FromSrgb(0.36f, 0.55f, 0.30f);
  grass.specular = 0.0f;
  grass.receives_shadow = true;
  scene.materials = {cloth_front, cloth_back, metal, gold, grass};

  Mesh flag;
  flag.front_material = 0;
  flag.back_material = 1;
  Mesh pole = CylinderMesh(Eigen::Vector3f::Zero(), pole_radius, pole_height, 16);
  pole.front_material = 2;
  Mesh finial = SphereMesh(Eigen::Vector3f(0, pole_height + 0.04f, 0), 0.06f, 16);
  finial.front_material = 3;
  Mesh ground = GroundMesh(0.75f, 0.0f, 400.0f);
  ground.front_material = 4;
  flag.casts_shadow = pole.casts_shadow = finial.casts_shadow = true;
  scene.meshes = {flag, pole, finial, ground};

  // Fine enough that a flag filling a 1920 x 1080 picture is still minified or near it: the
  // filtered pattern's edges stay sharp up close (texture_filter.hpp).
  scene.pattern = MakePattern(design, kPatternWidth, kPatternHeight);
  Light sun;
  sun.kind = Light::kDirectional;
  sun.vector = Eigen::Vector3f(0.4f, 0.8f, 0.6f).normalized();
  sun.colour = Eigen::Vector3f(1.0f, 0.97f, 0.9f);
  Light fill;
  fill.kind = Light::kPoint;
  fill.vector = Eigen::Vector3f(3.0f, 2.5f, 5.0f);
  fill.colour = Eigen::Vector3f(0.12f, 0.12f, 0.15f);
  // The sky and the ground light the scene from every side: the sky's blue from above, the
  // grass's green from below, and the bright sky opposite the sun; none of them makes
  // highlights. A surface turned from the sun still reads (a hemisphere light in three
  // directional parts, which OpenGL's fixed pipeline draws the same way).
  const auto diffuse_light = [](Eigen::Vector3f toward, Eigen::Vector3f colour) {
    Light light;
    light.vector = toward.normalized();
    light.colour = colour;
    light.specular = false;
    return light;
  };
  const Light from_sky = diffuse_light({0, 1, 0}, {0.07f, 0.08f, 0.11f});
  const Light from_ground = diffuse_light({0, -1, 0}, {0.05f, 0.07f, 0.04f});
  const Light far_sky = diffuse_light({-0.3f, 0.35f, -0.88f}, {0.12f, 0.13f, 0.16f});
  scene.lighting.ambient = Eigen::Vector3f(0.06f, 0.07f, 0.09f);
  scene.lighting.lights = {sun, fill, from_sky, from_ground, far_sky};
  scene.shadow_light = 0;
  return scene;
}

}  // namespace flagsim::render
