// What the renderer draws: triangle meshes with a front and an optional back material, and the
// scene around them (materials, the flag's pattern, lights, sky).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "server/render/pattern.hpp"
#include "server/render/shading.hpp"

namespace flagsim::render {

struct Mesh {
  std::vector<Eigen::Vector3f> positions;          ///< m, world frame
  std::vector<Eigen::Vector3f> normals;            ///< unit, on the front side
  std::vector<Eigen::Vector2f> uvs;                ///< pattern coordinates
  std::vector<std::array<uint32_t, 3>> triangles;  ///< counter-clockwise seen from the front
  std::vector<std::array<uint32_t, 2>> edges;      ///< wireframe: every edge once, first -> second
  int front_material = 0;                          ///< index into RenderScene::materials
  int back_material = -1;                          ///< -1: back faces are culled
  bool casts_shadow = false;                       ///< on the ground, in the shadow light (ground_shadow.hpp)
};

struct RenderScene {
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  Texture pattern;  ///< for materials with `patterned`
  Lighting lighting;
  int shadow_light = -1;  ///< the directional light whose shadow the ground receives; -1: none
  Eigen::Vector3f sky_top{0.33f, 0.55f, 0.85f};      ///< background at the image's top, RGB 0..1
  Eigen::Vector3f sky_horizon{0.80f, 0.87f, 0.94f};  ///< background at its bottom
};

/// The flag as a mesh: cols x rows nodes (positions in three arrays, node r * cols + c; row 0
/// the top edge, column 0 on the pole), two triangles per cell as the simulation cuts them,
/// normals from central differences across the grid. Topology is rebuilt only when the grid
/// changes; positions and normals every call.
void UpdateFlagMesh(int cols, int rows, const float* x, const float* y, const float* z, Mesh* mesh);

/// A closed cylinder side from `base` up `height` metres, `segments` around.
Mesh CylinderMesh(const Eigen::Vector3f& base, float radius, float height, int segments);
/// A sphere of `segments` around and segments / 2 from pole to pole.
Mesh SphereMesh(const Eigen::Vector3f& centre, float radius, int segments);
/// A square of side `size` on the plane y = 0, centred at (x, z); its (u, v) are (x, z).
Mesh GroundMesh(float x, float z, float size);

/// The flag (empty until UpdateFlagMesh), its pole and finial, the ground, sun and fill light;
/// the flag, the pole and the finial cast a shadow in the sun on the ground. Mesh 0 is the flag.
RenderScene DefaultRenderScene(float pole_height, float pole_radius = 0.03f,
                               FlagDesign design = FlagDesign::kNordicCross);

}  // namespace flagsim::render
