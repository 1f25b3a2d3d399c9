#include "forces.hpp"

#include <algorithm>
#include <cmath>

namespace flagsim::sim {
namespace {

/// m: the shortest length divided by; 1 / kShortest^2 stays finite in float.
constexpr float kShortest = 1e-9f;

// The kernels below take every array as a __restrict parameter (GCC honours restrict on
// parameters, not on locals), so that each loop over a grid row vectorises.

/// Springs a -> a + offset for a in [begin, end):
/// f_a = (k (|d| - L) / |d| + c (dv . d) / |d|^2) d, with d = x_b - x_a, dv = v_b - v_a.
template <typename Real>
void SpringKernel(const Real* __restrict x, const Real* __restrict y, const Real* __restrict z,
                  const Real* __restrict vx, const Real* __restrict vy, const Real* __restrict vz,
                  Real* __restrict fx, Real* __restrict fy, Real* __restrict fz, int begin, int end,
                  int offset, Real k, Real damping, Real rest) {
  for (int a = begin; a < end; ++a) {
    const int b = a + offset;
    const Real dx = x[b] - x[a], dy = y[b] - y[a], dz = z[b] - z[a];
    const Real length_squared = dx * dx + dy * dy + dz * dz;
    // A zero-length spring has d = 0 and so no force; the floor only keeps 1/|d| finite.
    const Real inverse = Real(1) / std::max(std::sqrt(length_squared), Real(kShortest));
    const Real closing = (vx[b] - vx[a]) * dx + (vy[b] - vy[a]) * dy + (vz[b] - vz[a]) * dz;
    const Real scale =
        k * (length_squared * inverse - rest) * inverse + damping * closing * inverse * inverse;
    fx[a] = scale * dx;
    fy[a] = scale * dy;
    fz[a] = scale * dz;
  }
}

/// Wind on triangles (p, q, s) = (p0 + i, q0 + i, s0 + i) for i in [0, n), wind (wx, wy, wz)[i]:
/// a third of C A n (n . w) each. With e = (q - p) x (s - p), |e| = 2A and n = e / |e|:
/// C A n (n . w) / 3 = (C / 6) e (e . w) / |e|. Relative wind subtracts the face's mean velocity.
template <typename Real>
void WindKernel(const Real* __restrict x, const Real* __restrict y, const Real* __restrict z,
                const Real* __restrict vx, const Real* __restrict vy, const Real* __restrict vz,
                const Real* __restrict wx, const Real* __restrict wy, const Real* __restrict wz,
                Real* __restrict fx, Real* __restrict fy, Real* __restrict fz, int p0, int q0, int s0, int n,
                Real share, Real relative) {
  const Real third = Real(1) / Real(3);
  for (int i = 0; i < n; ++i) {
    const int p = p0 + i, q = q0 + i, s = s0 + i;
    const Real ax = x[q] - x[p], ay = y[q] - y[p], az = z[q] - z[p];
    const Real bx = x[s] - x[p], by = y[s] - y[p], bz = z[s] - z[p];
    const Real ex = ay * bz - az * by, ey = az * bx - ax * bz, ez = ax * by - ay * bx;
    const Real ux = wx[i] - relative * third * (vx[p] + vx[q] + vx[s]);
    const Real uy = wy[i] - relative * third * (vy[p] + vy[q] + vy[s]);
    const Real uz = wz[i] - relative * third * (vz[p] + vz[q] + vz[s]);
    const Real norm = std::max(std::sqrt(ex * ex + ey * ey + ez * ez), Real(kShortest * kShortest));
    const Real scale = share * (ex * ux + ey * uy + ez * uz) / norm;
    fx[i] = scale * ex;
    fy[i] = scale * ey;
    fz[i] = scale * ez;
  }
}

/// f[i] += sign * g[i] for i in [0, n).
template <typename Real>
void AddKernel(Real* __restrict fx, Real* __restrict fy, Real* __restrict fz, const Real* __restrict gx,
               const Real* __restrict gy, const Real* __restrict gz, int n, Real sign) {
  for (int i = 0; i < n; ++i) {
    fx[i] += sign * gx[i];
    fy[i] += sign * gy[i];
    fz[i] += sign * gz[i];
  }
}

}  // namespace

template <typename Real>
void ForceEvaluator<Real>::Resize(const ClothModel<Real>& model) {
  const size_t nodes = model.num_nodes(), cells = model.num_cells();
  spring_.resize(model.families.size());
  for (NodeForces<Real>& family : spring_) {
    family.x.resize(nodes);
    family.y.resize(nodes);
    family.z.resize(nodes);
  }
  for (NodeForces<Real>* faces : {&upper_, &lower_}) {
    faces->x.resize(cells);
    faces->y.resize(cells);
    faces->z.resize(cells);
  }
  wind_x_.resize(model.cols - 1);
  wind_y_.resize(model.cols - 1);
  wind_z_.resize(model.cols - 1);
}

template <typename Real>
void ForceEvaluator<Real>::SampleWind(const ClothModel<Real>& model, const WindField& wind, double t) {
  // Gusts vary along the flag; one sample per cell column, at the column's middle.
  for (int c = 0; c + 1 < model.cols; ++c) {
    const Vec3 w = wind.At(t, (c + 0.5) * double(model.dx));
    wind_x_[c] = Real(w[0]);
    wind_y_[c] = Real(w[1]);
    wind_z_[c] = Real(w[2]);
  }
}

// Every spring whose first node is in row r, family by family.
template <typename Real>
void ForceEvaluator<Real>::SpringRow(const ClothModel<Real>& model, const ClothState<Real>& state, int r) {
  for (size_t f = 0; f < model.families.size(); ++f) {
    const SpringFamily<Real>& family = model.families[f];
    if (r + family.dr >= model.rows) continue;
    NodeForces<Real>& out = spring_[f];
    SpringKernel(state.x.data(), state.y.data(), state.z.data(), state.vx.data(), state.vy.data(),
                 state.vz.data(), out.x.data(), out.y.data(), out.z.data(),
                 model.index(r, family.first_col()), model.index(r, family.end_col(model.cols)),
                 family.dr * model.cols + family.dc, family.stiffness, family.damping, family.rest_length);
  }
}

// The two triangles of each cell in row r: upper (r, c) (r+1, c) (r, c+1) and
// lower (r+1, c) (r+1, c+1) (r, c+1). Along the row each corner runs over consecutive nodes.
template <typename Real>
void ForceEvaluator<Real>::WindRow(const ClothModel<Real>& model, const SimParams& params,
                                   const ClothState<Real>& state, int r) {
  const Real share = Real(params.wind_coefficient / 6.0);
  const Real relative = params.relative_wind ? Real(1) : Real(0);
  const int n = model.cols - 1, cell = r * n, top = model.index(r, 0), bottom = model.index(r + 1, 0);
  const struct {
    NodeForces<Real>* out;
    int p, q, s;
  } triangles[2] = {{&upper_, top, bottom, top + 1}, {&lower_, bottom, bottom + 1, top + 1}};
  for (const auto& triangle : triangles) {
    WindKernel(state.x.data(), state.y.data(), state.z.data(), state.vx.data(), state.vy.data(),
               state.vz.data(), wind_x_.data(), wind_y_.data(), wind_z_.data(), triangle.out->x.data() + cell,
               triangle.out->y.data() + cell, triangle.out->z.data() + cell, triangle.p, triangle.q,
               triangle.s, n, share, relative);
  }
}

// Node row r sums, in a fixed order: gravity and friction, its springs (as first node +f, as
// far node -f), then its up to six triangles' wind shares.
template <typename Real>
void ForceEvaluator<Real>::GatherRow(const ClothModel<Real>& model, const SimParams& params,
                                     const ClothState<Real>& state, int r, ForceTerms terms,
                                     NodeForces<Real>* forces) const {
  const int cols = model.cols, rows = model.rows, row = r * cols;
  Real* fx = forces->x.data() + row;
  Real* fy = forces->y.data() + row;
  Real* fz = forces->z.data() + row;
  const Real gravity = Real(params.gravity), friction = Real(AirFriction(params));
  for (int c = 0; c < cols; ++c) {
    const Real m = model.mass[row + c];
    fx[c] = -friction * m * state.vx[row + c];
    fy[c] = -m * gravity - friction * m * state.vy[row + c];
    fz[c] = -friction * m * state.vz[row + c];
  }
  // Adds sign * g over columns [first, end) of this row, g read at index (source + c).
  const auto add = [&](const NodeForces<Real>& g, int source, int first, int end, Real sign) {
    AddKernel(fx + first, fy + first, fz + first, g.x.data() + source + first, g.y.data() + source + first,
              g.z.data() + source + first, end - first, sign);
  };
  for (size_t f = 0; terms == ForceTerms::kAll && f < model.families.size(); ++f) {
    const SpringFamily<Real>& family = model.families[f];
    const int first = family.first_col(), end = family.end_col(cols);
    // as first nodes of springs (r, c) -> (r + dr, c + dc)
    if (r + family.dr < rows) add(spring_[f], row, first, end, Real(1));
    // as far nodes of springs starting at (r - dr, c - dc)
    if (r - family.dr >= 0) {
      add(spring_[f], row - family.dr * cols - family.dc, first + family.dc, end + family.dc, Real(-1));
    }
  }
  // Triangles touching node (r, c): upper of cells (r, c) (r-1, c) (r, c-1);
  // lower of cells (r-1, c) (r-1, c-1) (r, c-1). Cell (i, j) has index i (cols - 1) + j.
  const int n = cols - 1;
  const auto add_faces = [&](const NodeForces<Real>& faces, int cell_row, int shift) {
    if (cell_row < 0 || cell_row >= rows - 1) return;
    add(faces, cell_row * n - shift, shift, n + shift, Real(1));
  };
  add_faces(upper_, r, 0);
  add_faces(upper_, r - 1, 0);
  add_faces(upper_, r, 1);
  add_faces(lower_, r - 1, 0);
  add_faces(lower_, r - 1, 1);
  add_faces(lower_, r, 1);
}

template <typename Real>
void ForceEvaluator<Real>::Evaluate(const ClothModel<Real>& model, const SimParams& params,
                                    const WindField& wind, const ClothState<Real>& state, double t,
                                    NodeForces<Real>* forces, ForceTerms terms,
                                    const std::function<void(int)>& after_row) {
  Resize(model);
  SampleWind(model, wind, t);
  forces->x.resize(model.num_nodes());
  forces->y.resize(model.num_nodes());
  forces->z.resize(model.num_nodes());
  const int rows = model.rows;
  // One fork per evaluation: springs and wind per row, a barrier, then each row gathers.
#pragma omp parallel num_threads(params.threads) if (params.threads > 1)
  {
#pragma omp for schedule(static)
    for (int r = 0; r < rows; ++r) {
      if (terms == ForceTerms::kAll) SpringRow(model, state, r);
      if (r + 1 < rows) WindRow(model, params, state, r);
    }
#pragma omp for schedule(static)
    for (int r = 0; r < rows; ++r) {
      GatherRow(model, params, state, r, terms, forces);
      if (after_row) after_row(r);
    }
  }
}

template class ForceEvaluator<float>;
template class ForceEvaluator<double>;

}  // namespace flagsim::sim
