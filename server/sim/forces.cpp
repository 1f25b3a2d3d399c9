#include "forces.hpp"

#include <cmath>

namespace flagsim::sim {

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

// Springs whose first node is in row r: f_a = (k (|d| - L) / |d| + c (dv . d) / |d|^2) d.
template <typename Real>
void ForceEvaluator<Real>::SpringRow(const ClothModel<Real>& model, const ClothState<Real>& state,
                                     int r) {
  const Real* __restrict x = state.x.data();
  const Real* __restrict y = state.y.data();
  const Real* __restrict z = state.z.data();
  const Real* __restrict vx = state.vx.data();
  const Real* __restrict vy = state.vy.data();
  const Real* __restrict vz = state.vz.data();
  for (size_t f = 0; f < model.families.size(); ++f) {
    const SpringFamily<Real>& family = model.families[f];
    if (r + family.dr >= model.rows) continue;
    const int offset = family.dr * model.cols + family.dc;
    const Real k = family.stiffness, damping = family.damping, rest = family.rest_length;
    Real* __restrict fx = spring_[f].x.data();
    Real* __restrict fy = spring_[f].y.data();
    Real* __restrict fz = spring_[f].z.data();
    const int begin = model.index(r, family.first_col()), end = model.index(r, family.end_col(model.cols));
    for (int a = begin; a < end; ++a) {
      const int b = a + offset;
      const Real dx = x[b] - x[a], dy = y[b] - y[a], dz = z[b] - z[a];
      const Real length_squared = dx * dx + dy * dy + dz * dz;
      const Real length = std::sqrt(length_squared);
      const Real inverse = length > Real(0) ? Real(1) / length : Real(0);
      const Real closing = (vx[b] - vx[a]) * dx + (vy[b] - vy[a]) * dy + (vz[b] - vz[a]) * dz;
      const Real scale = k * (length - rest) * inverse + damping * closing * inverse * inverse;
      fx[a] = scale * dx;
      fy[a] = scale * dy;
      fz[a] = scale * dz;
    }
  }
}

// Wind on the two triangles of each cell in row r: a third of C A n (n . w) for each node.
// With e = edge1 x edge2 (|e| = 2A, n = e / |e|): C A n (n . w) = (C / 2) e (e . w) / |e|.
template <typename Real>
void ForceEvaluator<Real>::WindRow(const ClothModel<Real>& model, const SimParams& params,
                                   const ClothState<Real>& state, int r) {
  const Real share = Real(params.wind_coefficient / 6.0);
  const Real relative = params.relative_wind ? Real(1) : Real(0);
  const Real* x = state.x.data();
  const Real* y = state.y.data();
  const Real* z = state.z.data();
  const int cols = model.cols;
  for (int c = 0; c + 1 < cols; ++c) {
    const int cell = r * (cols - 1) + c;
    const int corner[4] = {model.index(r, c), model.index(r + 1, c), model.index(r, c + 1),
                           model.index(r + 1, c + 1)};
    // upper: corners 0 1 2; lower: corners 1 3 2.
    const int triangles[2][3] = {{corner[0], corner[1], corner[2]}, {corner[1], corner[3], corner[2]}};
    NodeForces<Real>* out[2] = {&upper_, &lower_};
    for (int t = 0; t < 2; ++t) {
      const int p = triangles[t][0], q = triangles[t][1], s = triangles[t][2];
      const Real ax = x[q] - x[p], ay = y[q] - y[p], az = z[q] - z[p];
      const Real bx = x[s] - x[p], by = y[s] - y[p], bz = z[s] - z[p];
      const Real ex = ay * bz - az * by, ey = az * bx - ax * bz, ez = ax * by - ay * bx;
      const Real third = Real(1) / Real(3);
      const Real wx = wind_x_[c] - relative * third * (state.vx[p] + state.vx[q] + state.vx[s]);
      const Real wy = wind_y_[c] - relative * third * (state.vy[p] + state.vy[q] + state.vy[s]);
      const Real wz = wind_z_[c] - relative * third * (state.vz[p] + state.vz[q] + state.vz[s]);
      const Real norm = std::sqrt(ex * ex + ey * ey + ez * ez);
      const Real scale = norm > Real(0) ? share * (ex * wx + ey * wy + ez * wz) / norm : Real(0);
      out[t]->x[cell] = scale * ex;
      out[t]->y[cell] = scale * ey;
      out[t]->z[cell] = scale * ez;
    }
  }
}

// Node row r sums, in a fixed order: gravity and friction, its springs (as first node +f, as
// far node -f), then its up to six triangles' wind shares.
template <typename Real>
void ForceEvaluator<Real>::GatherRow(const ClothModel<Real>& model, const SimParams& params,
                                     const ClothState<Real>& state, int r,
                                     NodeForces<Real>* forces) const {
  const int cols = model.cols, rows = model.rows, row = r * cols;
  Real* __restrict fx = forces->x.data() + row;
  Real* __restrict fy = forces->y.data() + row;
  Real* __restrict fz = forces->z.data() + row;
  const Real gravity = Real(params.gravity), friction = Real(AirFriction(params));
  for (int c = 0; c < cols; ++c) {
    const Real m = model.mass[row + c];
    fx[c] = -friction * m * state.vx[row + c];
    fy[c] = -m * gravity - friction * m * state.vy[row + c];
    fz[c] = -friction * m * state.vz[row + c];
  }
  for (size_t f = 0; f < model.families.size(); ++f) {
    const SpringFamily<Real>& family = model.families[f];
    const NodeForces<Real>& spring = spring_[f];
    const int first = family.first_col(), end = family.end_col(cols);
    if (r + family.dr < rows) {  // this row's nodes as first nodes
      for (int c = first; c < end; ++c) {
        fx[c] += spring.x[row + c];
        fy[c] += spring.y[row + c];
        fz[c] += spring.z[row + c];
      }
    }
    if (r - family.dr >= 0) {  // as far nodes of springs starting at (r - dr, c - dc)
      const int offset = family.dr * cols + family.dc;
      for (int c = first + family.dc; c < end + family.dc; ++c) {
        fx[c] -= spring.x[row + c - offset];
        fy[c] -= spring.y[row + c - offset];
        fz[c] -= spring.z[row + c - offset];
      }
    }
  }
  // Triangles touching node (r, c): upper of cells (r, c) (r-1, c) (r, c-1);
  // lower of cells (r-1, c) (r-1, c-1) (r, c-1). Cell (i, j) has index i (cols - 1) + j.
  const int cell_cols = cols - 1;
  auto add = [&](const NodeForces<Real>& faces, int cell_row, int first, int end, int shift) {
    if (cell_row < 0 || cell_row >= rows - 1) return;
    const int base = cell_row * cell_cols - shift;
    for (int c = first; c < end; ++c) {
      fx[c] += faces.x[base + c];
      fy[c] += faces.y[base + c];
      fz[c] += faces.z[base + c];
    }
  };
  add(upper_, r, 0, cols - 1, 0);
  add(upper_, r - 1, 0, cols - 1, 0);
  add(upper_, r, 1, cols, 1);
  add(lower_, r - 1, 0, cols - 1, 0);
  add(lower_, r - 1, 1, cols, 1);
  add(lower_, r, 1, cols, 1);
}

template <typename Real>
void ForceEvaluator<Real>::Evaluate(const ClothModel<Real>& model, const SimParams& params,
                                    const WindField& wind, const ClothState<Real>& state, double t,
                                    NodeForces<Real>* forces) {
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
      SpringRow(model, state, r);
      if (r + 1 < rows) WindRow(model, params, state, r);
    }
#pragma omp for schedule(static)
    for (int r = 0; r < rows; ++r) GatherRow(model, params, state, r, forces);
  }
}

template class ForceEvaluator<float>;
template class ForceEvaluator<double>;

}  // namespace flagsim::sim
