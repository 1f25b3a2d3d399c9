// A flag pose for benchmarks: cols x rows nodes of the default 1.5 m x 1.0 m flag rippled by a
// travelling wave, the same whatever the grid, so that renderers are compared on one shape.
#pragma once

#include <cmath>
#include <vector>

#include "server/render/mesh.hpp"

namespace flagsim::bench {

struct FlagPose {
  std::vector<float> x, y, z;
};

inline FlagPose RippledFlag(int cols, int rows, float phase = 0.0f) {
  FlagPose pose;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const float u = float(c) / (cols - 1), v = float(r) / (rows - 1);
      const float wave = 0.12f * u * std::sin(8.0f * u - 1.5f * v + phase);
      pose.x.push_back(1.45f * u - 0.4f * wave * wave);
      pose.y.push_back(2.98f - 1.0f * v - 0.12f * u * u);
      pose.z.push_back(wave + 0.05f * u * std::sin(17.0f * u + 5.0f * v));
    }
  }
  return pose;
}

/// The default render scene with the rippled flag in place.
inline render::RenderScene BenchScene(int cols, int rows, float phase = 0.0f) {
  render::RenderScene scene = render::DefaultRenderScene(3.0f);
  const FlagPose pose = RippledFlag(cols, rows, phase);
  render::UpdateFlagMesh(cols, rows, pose.x.data(), pose.y.data(), pose.z.data(), &scene.meshes[0]);
  return scene;
}

}  // namespace flagsim::bench
