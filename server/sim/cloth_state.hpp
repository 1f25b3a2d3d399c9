// The mutable part of the flag: node positions and velocities (structure of arrays, so that
// force loops over a grid row run on contiguous memory), and the clock.
#pragma once

#include <cstdint>
#include <vector>

#include "server/sim/cloth_model.hpp"

namespace flagsim::sim {

template <typename Real>
struct ClothState {
  std::vector<Real> x, y, z;     ///< m, world frame, per node
  std::vector<Real> vx, vy, vz;  ///< m/s, per node
  double time = 0;               ///< s, simulated
  int64_t step = 0;              ///< steps taken

  int num_nodes() const { return static_cast<int>(x.size()); }
};

/// The flag flat at its rest positions, at rest, at time 0.
template <typename Real>
ClothState<Real> RestState(const ClothModel<Real>& model) {
  ClothState<Real> state;
  state.x = model.rest_x;
  state.y = model.rest_y;
  state.z = model.rest_z;
  state.vx.assign(model.num_nodes(), Real(0));
  state.vy.assign(model.num_nodes(), Real(0));
  state.vz.assign(model.num_nodes(), Real(0));
  return state;
}

/// XXH3-64 over the bytes of x, y, z, vx, vy, vz in that order: equal hashes mean equal
/// states, bit for bit. Time and step are not included (they are published beside the hash).
template <typename Real>
uint64_t StateHash(const ClothState<Real>& state);

/// J: sum over the free nodes of m |v|^2 / 2, in double, node by node in index order (the same
/// at any thread count). Pinned nodes (inverse mass 0) ride the pole and are left out.
template <typename Real>
double KineticEnergy(const ClothModel<Real>& model, const ClothState<Real>& state);

}  // namespace flagsim::sim
