// The per-node stages explicit integrators are made of, and the loop that runs them row by row.
//   Drift   x' = x0 + h u          (u a velocity: positions move)
//   Kick    v' = v0 + h M^-1 f     (f a force: velocities change)
// Each stage reads and writes node i's entries only, so the output may be the input it updates
// (x' and x0 the same arrays) and any thread count gives the same bits. An integrator runs its
// stages on one grid row after another, while the row is in cache. Pinned nodes have inverse
// mass 0: a kick leaves their velocity as it was (0), so they never move.
#pragma once

#include <vector>

#include "server/parallel/worker_pool.hpp"
#include "server/sim/cloth_state.hpp"

namespace flagsim::sim {

/// Nodes [begin, end): one grid row, or any run of consecutive nodes.
struct NodeRange {
  int begin = 0, end = 0;
};

/// A 3-vector per node as three arrays, the layout of positions, velocities and forces (Real, or
/// const Real for a stage's inputs).
template <typename T>
struct NodeArrays {
  T* x;
  T* y;
  T* z;
};

template <typename Real>
NodeArrays<Real> Positions(ClothState<Real>* state) {
  return {state->x.data(), state->y.data(), state->z.data()};
}
template <typename Real>
NodeArrays<const Real> Positions(const ClothState<Real>& state) {
  return {state.x.data(), state.y.data(), state.z.data()};
}
template <typename Real>
NodeArrays<Real> Velocities(ClothState<Real>* state) {
  return {state->vx.data(), state->vy.data(), state->vz.data()};
}
template <typename Real>
NodeArrays<const Real> Velocities(const ClothState<Real>& state) {
  return {state.vx.data(), state.vy.data(), state.vz.data()};
}
/// Any per-node vectors with x, y, z arrays (NodeForces, NodeVectors).
template <class Vectors>
auto Arrays(Vectors* vectors) -> NodeArrays<typename decltype(vectors->x)::value_type> {
  return {vectors->x.data(), vectors->y.data(), vectors->z.data()};
}
template <class Vectors>
auto Arrays(const Vectors& vectors) -> NodeArrays<const typename decltype(vectors.x)::value_type> {
  return {vectors.x.data(), vectors.y.data(), vectors.z.data()};
}

/// Runs body(NodeRange) on every grid row, the rows shared among `threads` threads.
template <typename Body>
void ForEachRow(int rows, int cols, int threads, const Body& body) {
  ParallelFor(rows, threads, [&](int r) { body(NodeRange{r * cols, (r + 1) * cols}); });
}

/// (x0, u) => x' = x0 + h u over `nodes`. `out` may be `from`.
template <typename Real>
void Drift(NodeRange nodes, Real h, NodeArrays<const Real> u, NodeArrays<const Real> from,
           NodeArrays<Real> out) {
#pragma omp simd
  for (int i = nodes.begin; i < nodes.end; ++i) {
    out.x[i] = from.x[i] + h * u.x[i];
    out.y[i] = from.y[i] + h * u.y[i];
    out.z[i] = from.z[i] + h * u.z[i];
  }
}

/// (v0, f) => v' = v0 + (h m_i^-1) f over `nodes`. `out` may be `from`.
template <typename Real>
void Kick(NodeRange nodes, Real h, const std::vector<Real>& inverse_mass, NodeArrays<const Real> f,
          NodeArrays<const Real> from, NodeArrays<Real> out) {
#pragma omp simd
  for (int i = nodes.begin; i < nodes.end; ++i) {
    const Real a = h * inverse_mass[i];
    out.x[i] = from.x[i] + a * f.x[i];
    out.y[i] = from.y[i] + a * f.y[i];
    out.z[i] = from.z[i] + a * f.z[i];
  }
}

}  // namespace flagsim::sim
