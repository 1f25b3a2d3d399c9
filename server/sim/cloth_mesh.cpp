#include "server/sim/cloth_mesh.hpp"

#include <cstddef>

namespace flagsim::sim {

ClothMesh BuildClothMesh(int cols, int rows) {
  ClothMesh mesh;
  const auto node = [cols](int r, int c) { return r * cols + c; };
  mesh.triangles.reserve(std::size_t(2) * (cols - 1) * (rows - 1));
  for (int r = 0; r + 1 < rows; ++r) {
    for (int c = 0; c + 1 < cols; ++c) {
      mesh.triangles.push_back({node(r, c), node(r + 1, c), node(r, c + 1)});
      mesh.triangles.push_back({node(r + 1, c), node(r + 1, c + 1), node(r, c + 1)});
    }
  }
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (c + 1 < cols) mesh.edges.push_back({node(r, c), node(r, c + 1)});
      if (r + 1 < rows) mesh.edges.push_back({node(r, c), node(r + 1, c)});
      if (r + 1 < rows && c + 1 < cols) mesh.edges.push_back({node(r, c + 1), node(r + 1, c)});
    }
  }
  return mesh;
}

}  // namespace flagsim::sim
