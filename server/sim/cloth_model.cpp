#include "server/sim/cloth_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "server/sim/bending.hpp"
#include "server/sim/rest_imperfection.hpp"

namespace flagsim::sim {
namespace {

/// A node's share of the flag's area, in units of one cell: 1 inside, 1/2 on an edge,
/// 1/4 at a corner (bilinear lumping).
using Eigen3 = std::array<double, 3>;

constexpr double kPowerMargin =
    1.25;  ///< on w^2: the estimate came within 0.86 of the exact value on every grid tried

double AreaShare(int r, int c, int rows, int cols) {
  const double along = (c == 0 || c == cols - 1) ? 0.5 : 1.0;
  const double down = (r == 0 || r == rows - 1) ? 0.5 : 1.0;
  return along * down;
}

/// Which spring constant a matrix is built from: K from the stiffnesses, C from the dampings.
enum class SpringMatrix { kStiffness, kDamping };

/// The bending's constant in S: B for K, beta B for C.
template <typename Real>
double BendingConstant(const ClothModel<Real>& model, SpringMatrix matrix) {
  const double stiffness = model.bending_stiffness;
  return matrix == SpringMatrix::kStiffness ? stiffness : double(model.bending_damping) * stiffness;
}

/// out += M^-1/2 (constant Q) M^-1/2 v: Q = A sum_j s_j s_j^T over the interior nodes j.
template <typename Real>
void AddBendingProduct(const ClothModel<Real>& model, double constant, const std::vector<double>& scale,
                       const std::vector<Eigen3>& v, std::vector<Eigen3>* out) {
  if (constant == 0) return;
  const double area = double(model.dx) * double(model.dy);
  for (int r = 1; r + 1 < model.rows; ++r) {
    for (int c = 1; c + 1 < model.cols; ++c) {
      const BendingStencil s = StencilOf(model, r, c);
      for (int k = 0; k < 3; ++k) {
        double curvature = 0;
        for (int m = 0; m < 5; ++m) curvature += s.weights[m] * scale[s.nodes[m]] * v[s.nodes[m]][k];
        for (int m = 0; m < 5; ++m) (*out)[s.nodes[m]][k] += scale[s.nodes[m]] * constant * area * s.weights[m] * curvature;
      }
    }
  }
}

/// (M^-1/2 S M^-1/2) v over the free nodes, S = K or C of the springs at rest: each spring adds
/// s u u^T (v_a - v_b) to node a and the opposite to node b (u its rest direction, s its
/// constant).
template <typename Real>
void ApplyRestMatrix(const ClothModel<Real>& model, SpringMatrix matrix, const std::vector<double>& scale,
                     const std::vector<Eigen3>& v, std::vector<Eigen3>* out) {
  std::fill(out->begin(), out->end(), Eigen3{0, 0, 0});
  for (const SpringFamily<Real>& family : model.families) {
    for (int r = 0; r + family.dr < model.rows; ++r) {
      for (int c = family.first_col(); c < family.end_col(model.cols); ++c) {
        const int a = model.index(r, c), b = model.index(r + family.dr, c + family.dc);
        const double ux = double(model.rest_x[b]) - model.rest_x[a],
                     uy = double(model.rest_y[b]) - model.rest_y[a],
                     uz = double(model.rest_z[b]) - model.rest_z[a];
        const double length = std::sqrt(ux * ux + uy * uy + uz * uz);
        if (length == 0) continue;
        double along = 0;  // u . (scale_a v_a - scale_b v_b), with u not yet normalised
        along += ux * (scale[a] * v[a][0] - scale[b] * v[b][0]);
        along += uy * (scale[a] * v[a][1] - scale[b] * v[b][1]);
        along += uz * (scale[a] * v[a][2] - scale[b] * v[b][2]);
        const double constant = matrix == SpringMatrix::kStiffness ? family.stiffness : family.damping;
        const double f = constant * along / (length * length);
        const double u[3] = {ux, uy, uz};
        for (int k = 0; k < 3; ++k) {
          (*out)[a][k] += scale[a] * f * u[k];
          (*out)[b][k] -= scale[b] * f * u[k];
        }
      }
    }
  }
  AddBendingProduct(model, BendingConstant(model, matrix), scale, v, out);
}

/// Adds the bending's absolute row sums to K's and C's: sum_i' |Q_ii'| <= A sum over interior
/// j holding i of |s_j(i)| sum_m |s_j(m)|.
template <typename Real>
void AddBendingRowSums(const ClothModel<Real>& model, std::vector<double>* stiffness_sum,
                       std::vector<double>* damping_sum) {
  const double area = double(model.dx) * double(model.dy);
  for (int r = 1; r + 1 < model.rows; ++r) {
    for (int c = 1; c + 1 < model.cols; ++c) {
      const BendingStencil s = StencilOf(model, r, c);
      double total = 0;
      for (double weight : s.weights) total += std::abs(weight);
      for (int m = 0; m < 5; ++m) {
        const double row = area * std::abs(s.weights[m]) * total;
        (*stiffness_sum)[s.nodes[m]] += BendingConstant(model, SpringMatrix::kStiffness) * row;
        (*damping_sum)[s.nodes[m]] += BendingConstant(model, SpringMatrix::kDamping) * row;
      }
    }
  }
}

/// The largest eigenvalue of M^-1 K (or M^-1 C) at rest, estimated from below by power
/// iteration. The start is a checkerboard in the plane of the flag, close to the stiffest mode
/// of a grid, so few iterations get near it; the Rayleigh quotient never exceeds the true value.
template <typename Real>
double PowerIterationEigenvalue(const ClothModel<Real>& model, SpringMatrix matrix) {
  constexpr int kIterations = 48;
  const int n = model.num_nodes();
  std::vector<double> scale(n);  // M^-1/2, 0 for pinned nodes
  std::vector<Eigen3> v(n), w(n);
  for (int i = 0; i < n; ++i) {
    scale[i] = std::sqrt(double(model.inverse_mass[i]));
    const int r = i / model.cols, c = i % model.cols;
    const double sign = (r + c) % 2 == 0 ? 1.0 : -1.0;
    v[i] = scale[i] > 0 ? Eigen3{sign, 0.7 * sign * ((r % 3) - 1.0), 0.1 * ((c % 5) - 2.0)} : Eigen3{0, 0, 0};
  }
  double estimate = 0;
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    ApplyRestMatrix(model, matrix, scale, v, &w);
    double vv = 0, vw = 0, ww = 0;
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < 3; ++k) {
        vv += v[i][k] * v[i][k];
        vw += v[i][k] * w[i][k];
        ww += w[i][k] * w[i][k];
      }
    }
    if (vv == 0 || ww == 0) return 0;
    estimate = vw / vv;
    const double norm = 1 / std::sqrt(ww);
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < 3; ++k) v[i][k] = w[i][k] * norm;
    }
  }
  return estimate;
}

}  // namespace

template <typename Real>
void SetMaterialConstants(const SimParams& params, ClothModel<Real>* model) {
  const double cell_area = double(model->dx) * double(model->dy);
  for (SpringFamily<Real>& family : model->families) {
    const double modulus =
        family.kind == SpringKind::kStructural ? params.forces.stiffness : params.forces.shear_stiffness;
    // A spring stands for a strip of sheet dx dy / L wide and L long: k = modulus dx dy / L^2.
    // Compressed, it keeps `compression` of that (Choi and Ko 2002, "Stable but responsive
    // cloth": cloth resists compression far less than stretch, and buckles).
    const double L = double(family.rest_length);
    const double scale = cell_area / (L * L);
    family.stiffness = Real(modulus * scale);
    family.compression_stiffness = Real(params.compression * modulus * scale);
    family.damping = Real(params.forces.damping * scale);
  }
  model->bending_stiffness = Real(params.forces.bending_stiffness);
  const double stiffness = params.forces.stiffness;
  model->bending_damping = Real(stiffness > 0 ? params.forces.damping / stiffness : 0.0);
}

template <typename Real>
ClothModel<Real> BuildClothModel(const SimParams& params) {
  ClothModel<Real> model;
  model.cols = params.cols;
  model.rows = params.rows;
  const double dx = params.width / (params.cols - 1);
  const double dy = params.height / (params.rows - 1);
  model.dx = Real(dx);
  model.dy = Real(dy);
  model.pole_top = {0.0, params.pole_height, 0.0};

  const double diagonal = std::hypot(dx, dy);
  model.families = {
      {SpringKind::kStructural, 0, 1, Real(dx), 0, 0},  {SpringKind::kStructural, 1, 0, Real(dy), 0, 0},
      {SpringKind::kShear, 1, 1, Real(diagonal), 0, 0}, {SpringKind::kShear, 1, -1, Real(diagonal), 0, 0}};
  SetMaterialConstants(params, &model);

  const int n = model.num_nodes();
  const double density = params.mass / (params.width * params.height);  // kg/m^2
  const double top = params.pole_height - 0.02;  // the top edge hangs just below the finial
  model.mass.resize(n);
  model.inverse_mass.resize(n);
  model.rest_x.resize(n);
  model.rest_y.resize(n);
  model.rest_z.resize(n);
  for (int r = 0; r < params.rows; ++r) {
    for (int c = 0; c < params.cols; ++c) {
      const int i = model.index(r, c);
      model.mass[i] = Real(density * dx * dy * AreaShare(r, c, params.rows, params.cols));
      model.inverse_mass[i] = c == 0 ? Real(0) : Real(1) / model.mass[i];  // hoist edge pinned
      model.rest_x[i] = Real(params.pole_radius + c * dx);  // the hoist edge on the pole's surface
      model.rest_y[i] = Real(top - r * dy);
      model.rest_z[i] = Real(0);
    }
  }
  AddRestImperfection(params, &model);
  return model;
}

template <typename Real>
double StiffnessDampingRatio(const ClothModel<Real>& model) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const SpringFamily<Real>& family : model.families) {
    if (family.stiffness > 0) smallest = std::min(smallest, double(family.damping) / family.stiffness);
  }
  if (model.bending_stiffness > 0) smallest = std::min(smallest, double(model.bending_damping));
  return std::isfinite(smallest) ? smallest : 0.0;
}

template <typename Real>
FrequencyBound EstimateFrequencyBound(const ClothModel<Real>& model, double friction) {
  // Absolute row sums of K and C per node: a spring adds 2 |k| (diagonal and off-diagonal) to
  // both of its nodes' rows.
  std::vector<double> stiffness_sum(model.num_nodes(), 0.0), damping_sum(model.num_nodes(), 0.0);
  for (const SpringFamily<Real>& family : model.families) {
    for (int r = 0; r + family.dr < model.rows; ++r) {
      for (int c = family.first_col(); c < family.end_col(model.cols); ++c) {
        const int a = model.index(r, c), b = model.index(r + family.dr, c + family.dc);
        stiffness_sum[a] += 2 * family.stiffness;
        stiffness_sum[b] += 2 * family.stiffness;
        damping_sum[a] += 2 * family.damping;
        damping_sum[b] += 2 * family.damping;
      }
    }
  }
  AddBendingRowSums(model, &stiffness_sum, &damping_sum);
  FrequencyBound bound;
  bound.friction = friction;
  bound.stiffness_damping_ratio = StiffnessDampingRatio(model);
  for (int i = 0; i < model.num_nodes(); ++i) {
    if (model.pinned(i)) continue;
    const double inverse_mass = model.inverse_mass[i];
    bound.omega_squared = std::max(bound.omega_squared, stiffness_sum[i] * inverse_mass);
    bound.damping_rate = std::max(bound.damping_rate, damping_sum[i] * inverse_mass + friction);
  }
  // Gershgorin's bounds are safe but loose (by about 2x on these grids); the power iteration's
  // estimates, with a margin for what they have not yet converged to, are tighter.
  bound.omega_squared =
      std::min(bound.omega_squared, kPowerMargin * PowerIterationEigenvalue(model, SpringMatrix::kStiffness));
  bound.damping_rate = std::min(
      bound.damping_rate, kPowerMargin * PowerIterationEigenvalue(model, SpringMatrix::kDamping) + friction);
  return bound;
}

template ClothModel<float> BuildClothModel<float>(const SimParams&);
template ClothModel<double> BuildClothModel<double>(const SimParams&);
template void SetMaterialConstants<float>(const SimParams&, ClothModel<float>*);
template void SetMaterialConstants<double>(const SimParams&, ClothModel<double>*);
template FrequencyBound EstimateFrequencyBound<float>(const ClothModel<float>&, double);
template FrequencyBound EstimateFrequencyBound<double>(const ClothModel<double>&, double);
template double StiffnessDampingRatio<float>(const ClothModel<float>&);
template double StiffnessDampingRatio<double>(const ClothModel<double>&);

}  // namespace flagsim::sim
