#include "server/sim/bending.hpp"

#include <algorithm>

namespace flagsim::sim {
namespace {

/// k[i] = (L x)[i] for i in [begin, end), written as differences of differences, which keeps
/// float's rounding to that of the small differences rather than of the positions.
template <typename Real>
void CurvatureKernel(const Real* __restrict x, Real* __restrict k, int begin, int end, int cols, Real along,
                     Real down) {
  for (int i = begin; i < end; ++i) {
    const Real across_row = (x[i + 1] - x[i]) - (x[i] - x[i - 1]);
    const Real across_column = (x[i + cols] - x[i]) - (x[i] - x[i - cols]);
    k[i] = along * across_row + down * across_column;
  }
}

/// k[i] = (L (x + beta v))[i] for i in [begin, end), as above.
template <typename Real>
void DampedCurvatureKernel(const Real* __restrict x, const Real* __restrict v, Real* __restrict k, int begin,
                           int end, int cols, Real along, Real down, Real beta) {
  for (int i = begin; i < end; ++i) {
    const Real across_row = (x[i + 1] - x[i]) - (x[i] - x[i - 1]) + beta * ((v[i + 1] - v[i]) - (v[i] - v[i - 1]));
    const Real across_column =
        (x[i + cols] - x[i]) - (x[i] - x[i - cols]) + beta * ((v[i + cols] - v[i]) - (v[i] - v[i - cols]));
    k[i] = along * across_row + down * across_column;
  }
}

/// f[i] = scale ((k[i-1] + k[i+1]) along + (k[i-cols] + k[i+cols]) down + k[i] centre).
template <typename Real>
void LaplacianKernel(const Real* __restrict k, Real* __restrict f, int begin, int end, int cols, Real along,
                     Real down, Real centre, Real scale) {
  for (int i = begin; i < end; ++i) {
    f[i] = scale * (along * (k[i - 1] + k[i + 1]) + down * (k[i - cols] + k[i + cols]) + centre * k[i]);
  }
}

}  // namespace

template <typename Real>
LaplacianWeights LaplacianOf(const ClothModel<Real>& model) {
  LaplacianWeights weights;
  weights.along = 1.0 / (double(model.dx) * double(model.dx));
  weights.down = 1.0 / (double(model.dy) * double(model.dy));
  weights.centre = -2.0 * (weights.along + weights.down);
  return weights;
}

template <typename Real>
void CurvatureRows(const ClothModel<Real>& model, const Real* x, const Real* v, int begin, int end,
                   Real* curvature) {
  const LaplacianWeights weights = LaplacianOf(model);
  const Real along = Real(weights.along), down = Real(weights.down);
  const int cols = model.cols;
  for (int r = begin; r < end; ++r) {
    Real* row = curvature + r * cols;
    if (r == 0 || r + 1 == model.rows) {
      std::fill(row, row + cols, Real(0));
      continue;
    }
    const int first = r * cols + 1, last = (r + 1) * cols - 1;  // the row's interior nodes
    if (v == nullptr) {
      CurvatureKernel(x, curvature, first, last, cols, along, down);
    } else {
      DampedCurvatureKernel(x, v, curvature, first, last, cols, along, down, model.bending_damping);
    }
    row[0] = row[cols - 1] = Real(0);
  }
}

template <typename Real>
void BendingForceRows(const ClothModel<Real>& model, const Real* curvature, int begin, int end, Real* force) {
  const LaplacianWeights weights = LaplacianOf(model);
  const double area = double(model.dx) * double(model.dy);
  LaplacianKernel(curvature, force, begin * model.cols, end * model.cols, model.cols, Real(weights.along),
                  Real(weights.down), Real(weights.centre), Real(-double(model.bending_stiffness) * area));
}

template <typename Real>
BendingStencil StencilOf(const ClothModel<Real>& model, int r, int c) {
  const LaplacianWeights w = LaplacianOf(model);
  const int j = model.index(r, c), cols = model.cols;
  return {{j, j - 1, j + 1, j - cols, j + cols}, {w.centre, w.along, w.along, w.down, w.down}};
}

template <typename Real>
Real BendingProductAt(const ClothModel<Real>& model, const Real* p, int r, int c) {
  // (B Q p)_i = B A sum over interior j whose stencil holds i of s_j(i) (L p)_j: i itself and
  // its four neighbours, each weighted by its stencil's weight at i.
  const LaplacianWeights w = LaplacianOf(model);
  const auto laplacian_at = [&](int rj, int cj) -> double {
    if (!Interior(model.rows, model.cols, rj, cj)) return 0.0;
    const int j = model.index(rj, cj);
    return w.along * ((double(p[j + 1]) - p[j]) - (double(p[j]) - p[j - 1])) +
           w.down * ((double(p[j + model.cols]) - p[j]) - (double(p[j]) - p[j - model.cols]));
  };
  const double sum = w.centre * laplacian_at(r, c) + w.along * (laplacian_at(r, c - 1) + laplacian_at(r, c + 1)) +
                     w.down * (laplacian_at(r - 1, c) + laplacian_at(r + 1, c));
  return Real(double(model.bending_stiffness) * double(model.dx) * double(model.dy) * sum);
}

template <typename Real>
double BendingDiagonal(const ClothModel<Real>& model, int r, int c) {
  // Q_ii = A sum over interior j holding i of s_j(i)^2.
  const LaplacianWeights w = LaplacianOf(model);
  const auto interior = [&](int rj, int cj) { return Interior(model.rows, model.cols, rj, cj) ? 1.0 : 0.0; };
  const double sum = w.centre * w.centre * interior(r, c) +
                     w.along * w.along * (interior(r, c - 1) + interior(r, c + 1)) +
                     w.down * w.down * (interior(r - 1, c) + interior(r + 1, c));
  return double(model.bending_stiffness) * double(model.dx) * double(model.dy) * sum;
}

template <typename Real>
std::array<double, 3> CurvatureAt(const ClothModel<Real>& model, const std::vector<Real>& x,
                                  const std::vector<Real>& y, const std::vector<Real>& z, int r, int c) {
  const BendingStencil s = StencilOf(model, r, c);
  std::array<double, 3> k{0, 0, 0};
  const std::vector<Real>* coordinates[3] = {&x, &y, &z};
  for (int axis = 0; axis < 3; ++axis) {
    const std::vector<Real>& p = *coordinates[axis];
    for (int m = 1; m < 5; ++m) k[axis] += s.weights[m] * (double(p[s.nodes[m]]) - p[s.nodes[0]]);
  }
  return k;
}

template <typename Real>
double BendingEnergy(const ClothModel<Real>& model, const std::vector<Real>& x, const std::vector<Real>& y,
                     const std::vector<Real>& z) {
  double sum = 0;
  for (int r = 1; r + 1 < model.rows; ++r) {
    for (int c = 1; c + 1 < model.cols; ++c) {
      const std::array<double, 3> k = CurvatureAt(model, x, y, z, r, c);
      sum += k[0] * k[0] + k[1] * k[1] + k[2] * k[2];
    }
  }
  return 0.5 * double(model.bending_stiffness) * double(model.dx) * double(model.dy) * sum;
}

#define FLAGSIM_BENDING(Real)                                                                          \
  template LaplacianWeights LaplacianOf<Real>(const ClothModel<Real>&);                                \
  template void CurvatureRows<Real>(const ClothModel<Real>&, const Real*, const Real*, int, int, Real*); \
  template void BendingForceRows<Real>(const ClothModel<Real>&, const Real*, int, int, Real*);         \
  template BendingStencil StencilOf<Real>(const ClothModel<Real>&, int, int);                          \
  template Real BendingProductAt<Real>(const ClothModel<Real>&, const Real*, int, int);                \
  template double BendingDiagonal<Real>(const ClothModel<Real>&, int, int);                            \
  template std::array<double, 3> CurvatureAt<Real>(const ClothModel<Real>&, const std::vector<Real>&, \
                                                  const std::vector<Real>&, const std::vector<Real>&, int, int); \
  template double BendingEnergy<Real>(const ClothModel<Real>&, const std::vector<Real>&,               \
                                      const std::vector<Real>&, const std::vector<Real>&);
FLAGSIM_BENDING(float)
FLAGSIM_BENDING(double)
#undef FLAGSIM_BENDING

}  // namespace flagsim::sim
