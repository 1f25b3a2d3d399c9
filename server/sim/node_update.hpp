// The loops every explicit integrator is made of, over all nodes in grid rows (one OpenMP
// loop each; a node's update reads only that node, so any thread count gives the same bits).
// Pinned nodes have inverse mass 0: a kick leaves their velocity at 0, so they never move.
#pragma once

#include "cloth_model.hpp"
#include "cloth_state.hpp"
#include "forces.hpp"

namespace flagsim::sim {

/// Runs body(i) for every node i, the rows shared among `threads` threads.
template <typename Body>
void ForEachNode(int rows, int cols, int threads, const Body& body) {
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (int r = 0; r < rows; ++r) {
    for (int i = r * cols; i < (r + 1) * cols; ++i) body(i);
  }
}

/// v <- v + h M^-1 f.
template <typename Real>
void Kick(const ClothModel<Real>& model, const NodeForces<Real>& f, Real h, int threads,
          ClothState<Real>* state) {
  ForEachNode(model.rows, model.cols, threads, [&](int i) {
    const Real a = h * model.inverse_mass[i];
    state->vx[i] += a * f.x[i];
    state->vy[i] += a * f.y[i];
    state->vz[i] += a * f.z[i];
  });
}

/// x <- x + h v.
template <typename Real>
void Drift(const ClothModel<Real>& model, Real h, int threads, ClothState<Real>* state) {
  ForEachNode(model.rows, model.cols, threads, [&](int i) {
    state->x[i] += h * state->vx[i];
    state->y[i] += h * state->vy[i];
    state->z[i] += h * state->vz[i];
  });
}

}  // namespace flagsim::sim
