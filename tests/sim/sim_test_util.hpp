// Helpers shared by the sim tests: small hand-built models and sums over a state.
#pragma once

#include <array>
#include <cmath>

#include "server/sim/cloth_model.hpp"
#include "server/sim/cloth_state.hpp"
#include "server/sim/sim_params.hpp"
#include "server/sim/wind_field.hpp"

namespace flagsim::sim::testing {

/// Parameters with every external force off: no gravity, wind, friction.
inline SimParams Isolated() {
  SimParams params;
  params.forces.gravity = 0;
  params.forces.friction = 0;
  params.forces.wind_coefficient = 0;
  return params;
}

inline WindSettings NoWind() { return WindSettings{{0, 0, 0}, 0, 0}; }

/// Frees the pinned hoist edge: every node gets its inverse mass.
template <typename Real>
void Unpin(ClothModel<Real>* model) {
  for (int i = 0; i < model->num_nodes(); ++i) model->inverse_mass[i] = Real(1) / model->mass[i];
}

template <typename Real>
std::array<double, 3> Momentum(const ClothModel<Real>& model, const ClothState<Real>& state) {
  std::array<double, 3> p{};
  for (int i = 0; i < model.num_nodes(); ++i) {
    p[0] += double(model.mass[i]) * state.vx[i];
    p[1] += double(model.mass[i]) * state.vy[i];
    p[2] += double(model.mass[i]) * state.vz[i];
  }
  return p;
}

template <typename Real>
std::array<double, 3> CentreOfMass(const ClothModel<Real>& model, const ClothState<Real>& state) {
  std::array<double, 3> c{};
  double total = 0;
  for (int i = 0; i < model.num_nodes(); ++i) {
    c[0] += double(model.mass[i]) * state.x[i];
    c[1] += double(model.mass[i]) * state.y[i];
    c[2] += double(model.mass[i]) * state.z[i];
    total += model.mass[i];
  }
  for (double& value : c) value /= total;
  return c;
}

template <typename Real>
double KineticEnergy(const ClothModel<Real>& model, const ClothState<Real>& state) {
  double energy = 0;
  for (int i = 0; i < model.num_nodes(); ++i) {
    const double v2 = double(state.vx[i]) * state.vx[i] + double(state.vy[i]) * state.vy[i] +
                      double(state.vz[i]) * state.vz[i];
    energy += 0.5 * double(model.mass[i]) * v2;
  }
  return energy;
}

/// Spring energy sum k (|d| - L)^2 / 2 over every spring of every family, k the stiffness of the
/// spring's regime: its compression stiffness when |d| < L.
template <typename Real>
double SpringEnergy(const ClothModel<Real>& model, const ClothState<Real>& state) {
  double energy = 0;
  for (const SpringFamily<Real>& family : model.families) {
    for (int r = 0; r + family.dr < model.rows; ++r) {
      for (int c = family.first_col(); c < family.end_col(model.cols); ++c) {
        const int a = model.index(r, c), b = model.index(r + family.dr, c + family.dc);
        const double dx = double(state.x[b]) - state.x[a], dy = double(state.y[b]) - state.y[a],
                     dz = double(state.z[b]) - state.z[a];
        const double stretch = std::sqrt(dx * dx + dy * dy + dz * dz) - double(family.rest_length);
        const double k = stretch < 0 ? family.compression_stiffness : family.stiffness;
        energy += 0.5 * k * stretch * stretch;
      }
    }
  }
  return energy;
}

}  // namespace flagsim::sim::testing
