#include "server/sim/forces.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "server/parallel/worker_pool.hpp"
#include "server/sim/bending.hpp"

namespace flagsim::sim {
namespace {

// The kernels below take every array as a __restrict parameter (GCC honours restrict on
// parameters, not on locals), so that each loop over a grid row vectorises.

/// Springs a -> a + offset for a in [begin, end):
/// f_a = (k (|d| - L) / |d| + c (dv . d) / |d|^2) d, with d = x_b - x_a, dv = v_b - v_a, and
/// k = stretched if |d| >= L, compressed if |d| < L (Choi and Ko 2002's stretch/compression
/// split). The choice is a select, not a branch, so the loop still vectorises.
template <typename Real>
void SpringKernel(const Real* __restrict x, const Real* __restrict y, const Real* __restrict z,
                  const Real* __restrict vx, const Real* __restrict vy, const Real* __restrict vz,
                  Real* __restrict fx, Real* __restrict fy, Real* __restrict fz, int begin, int end,
                  int offset, Real stretched, Real compressed, Real damping, Real rest) {
  for (int a = begin; a < end; ++a) {
    const int b = a + offset;
    const Real dx = x[b] - x[a], dy = y[b] - y[a], dz = z[b] - z[a];
    const Real length_squared = dx * dx + dy * dy + dz * dz;
    // A zero-length spring has d = 0 and so no force; the floor only keeps 1/|d| finite.
    const Real inverse = Real(1) / std::max(std::sqrt(length_squared), Real(kShortestSpring));
    const Real closing = (vx[b] - vx[a]) * dx + (vy[b] - vy[a]) * dy + (vz[b] - vz[a]) * dz;
    const Real stretch = length_squared * inverse - rest;  // m: |d| - L
    const Real k = stretch < Real(0) ? compressed : stretched;
    const Real scale = k * stretch * inverse + damping * closing * inverse * inverse;
    fx[a] = scale * dx;
    fy[a] = scale * dy;
    fz[a] = scale * dz;
  }
}

/// Wind on the triangles of cells a in [begin, end): corners p = a + p_offset, q = p + q_offset,
/// s = p + s_offset, wind (wx, wy, wz)[a]; the result goes to f[a]: a third of C A n (n . w)
/// each. With e = (q - p) x (s - p), |e| = 2A and n = e / |e|:
/// C A n (n . w) / 3 = (C / 6) e (e . w) / |e|. Relative wind subtracts the face's mean velocity.
template <typename Real>
void WindKernel(const Real* __restrict x, const Real* __restrict y, const Real* __restrict z,
                const Real* __restrict vx, const Real* __restrict vy, const Real* __restrict vz,
                const Real* __restrict wx, const Real* __restrict wy, const Real* __restrict wz,
                Real* __restrict fx, Real* __restrict fy, Real* __restrict fz, int begin, int end,
                int p_offset, int q_offset, int s_offset, Real share, Real relative) {
  const Real third = Real(1) / Real(3);
  for (int a = begin; a < end; ++a) {
    const int p = a + p_offset, q = p + q_offset, s = p + s_offset;
    const Real ax = x[q] - x[p], ay = y[q] - y[p], az = z[q] - z[p];
    const Real bx = x[s] - x[p], by = y[s] - y[p], bz = z[s] - z[p];
    const Real ex = ay * bz - az * by, ey = az * bx - ax * bz, ez = ax * by - ay * bx;
    const Real ux = wx[a] - relative * third * (vx[p] + vx[q] + vx[s]);
    const Real uy = wy[a] - relative * third * (vy[p] + vy[q] + vy[s]);
    const Real uz = wz[a] - relative * third * (vz[p] + vz[q] + vz[s]);
    const Real norm =
        std::max(std::sqrt(ex * ex + ey * ey + ez * ez), Real(kShortestSpring * kShortestSpring));
    const Real scale = share * (ex * ux + ey * uy + ez * uz) / norm;
    fx[a] = scale * ex;
    fy[a] = scale * ey;
    fz[a] = scale * ez;
  }
}

/// The grid's spring families, at most: structural and shear, two directions each.
constexpr int kMaxSpringFamilies = 4;
/// Arrays a node's force is summed from: both ends of every family, six faces and the bending.
constexpr int kGatherSources = 2 * kMaxSpringFamilies + 7;

/// Where one grid row's contributions are read: source k holds column c's at [c]. Sources come
/// in a fixed order: per family, the springs' first ends then their far ends; then six faces;
/// then the bending.
template <typename Real>
struct GatherSources {
  const Real* x[kGatherSources];
  const Real* y[kGatherSources];
  const Real* z[kGatherSources];
};

/// Zero slots in front of the scratch arrays: the farthest a node reads back (a spring or a face
/// one row up, one column aside), and more than the bending's curvature needs either side.
int Padding(int cols) { return 2 * cols + 2; }

/// f[start + c] = 0 for c in [first, end).
template <typename Real>
void ZeroColumns(NodeForces<Real>* f, int start, int first, int end) {
  for (int c = first; c < end; ++c) f->x[start + c] = f->y[start + c] = f->z[start + c] = Real(0);
}

template <typename Real>
NodeForces<Real> ZeroForces(size_t slots) {
  NodeForces<Real> zero;
  zero.x.assign(slots, Real(0));
  zero.y.assign(slots, Real(0));
  zero.z.assign(slots, Real(0));
  return zero;
}

/// Source k is subtracted: the far ends of springs (every second of the first
/// 2 kMaxSpringFamilies sources). Known at compile time, so the sum needs no multiplications.
constexpr bool Subtracted(int k) { return k < 2 * kMaxSpringFamilies && k % 2 == 1; }

/// Sums each node's force, for i in [0, n): gravity and air friction from its mass and velocity,
/// then +- source[k][i] for k in a fixed order. One pass, every partial sum in registers.
template <typename Real>
void GatherKernel(const GatherSources<Real>& sources, const Real* __restrict mass, const Real* __restrict vx,
                  const Real* __restrict vy, const Real* __restrict vz, Real gravity, Real friction,
                  Real* __restrict fx, Real* __restrict fy, Real* __restrict fz, int n) {
#pragma omp simd
  for (int i = 0; i < n; ++i) {
    Real sx = -friction * mass[i] * vx[i];
    Real sy = -mass[i] * gravity - friction * mass[i] * vy[i];
    Real sz = -friction * mass[i] * vz[i];
#pragma GCC unroll 15
    for (int k = 0; k < kGatherSources; ++k) {
      if (Subtracted(k)) {
        sx -= sources.x[k][i];
        sy -= sources.y[k][i];
        sz -= sources.z[k][i];
      } else {
        sx += sources.x[k][i];
        sy += sources.y[k][i];
        sz += sources.z[k][i];
      }
    }
    fx[i] = sx;
    fy[i] = sy;
    fz[i] = sz;
  }
}

/// Whether an evaluation of `terms` sums a bending force: asked for, and the sheet has one.
template <typename Real>
bool Bends(const ClothModel<Real>& model, ForceTerms terms) {
  return Includes(terms, ForceTerms::kBending) && model.bending_stiffness > Real(0);
}

}  // namespace

// Scratch layout. Per-spring forces (per family) and per-face wind shares are stored on the node
// grid, at index Padding(cols) + node: a spring at its first node, a face at its cell's top-left
// node. Slots of springs and faces that do not exist (past the grid's edges, or the last row and
// column of cells) are never written and stay 0, as do the Padding(cols) slots in front, so a
// node reads its springs at fixed offsets (the far end of a spring from a at a - offset) and its
// six faces at i, i - 1, i - cols and i - cols - 1 with no bounds checks: a missing one adds 0.
// The curvature and the bending force are per node at the same index, with Padding(cols) zero
// slots after the nodes as well: the bending's Laplacian reads one row either side.

// Compared in place: Evaluate asks this every substep, and a vector made to compare would be a
// heap allocation each time.
template <typename Real>
bool ForceEvaluator<Real>::LaidOutFor(const ClothModel<Real>& model) const {
  if (layout_.size() != 2 + 2 * model.families.size() || layout_[0] != model.cols || layout_[1] != model.rows)
    return false;
  for (size_t f = 0; f < model.families.size(); ++f)
    if (layout_[2 + 2 * f] != model.families[f].dr || layout_[3 + 2 * f] != model.families[f].dc) return false;
  return true;
}

template <typename Real>
void ForceEvaluator<Real>::Resize(const ClothModel<Real>& model) {
  if (model.families.size() > kMaxSpringFamilies) throw std::invalid_argument("too many spring families");
  if (LaidOutFor(model)) return;
  layout_ = {model.cols, model.rows};
  for (const SpringFamily<Real>& family : model.families) layout_.insert(layout_.end(), {family.dr, family.dc});
  // Fresh zeros: slots a new layout never writes must not keep an old layout's forces.
  const size_t slots = Padding(model.cols) + model.num_nodes();
  spring_.assign(model.families.size(), ZeroForces<Real>(slots));
  upper_ = lower_ = ZeroForces<Real>(slots);
  curvature_ = bending_ = ZeroForces<Real>(slots + Padding(model.cols));  // padded after the nodes too
  zero_.assign(model.num_nodes(), Real(0));
  column_wind_x_.resize(model.cols - 1);
  column_wind_y_.resize(model.cols - 1);
  column_wind_z_.resize(model.cols - 1);
  wind_x_.assign(model.num_nodes(), Real(0));
  wind_y_.assign(model.num_nodes(), Real(0));
  wind_z_.assign(model.num_nodes(), Real(0));
}

template <typename Real>
void ForceEvaluator<Real>::SampleWind(const ClothModel<Real>& model, const WindField& wind, double t) {
  // Gusts vary along the flag; one sample per cell column, at the column's middle.
  const int columns = model.cols - 1;
  column_s_.resize(columns);
  column_wind_.resize(columns);
  for (int c = 0; c < columns; ++c) column_s_[c] = (c + 0.5) * double(model.dx);
  wind.Along(t, column_s_.data(), columns, column_wind_.data());
  for (int c = 0; c < columns; ++c) {
    column_wind_x_[c] = Real(column_wind_[c][0]);
    column_wind_y_[c] = Real(column_wind_[c][1]);
    column_wind_z_[c] = Real(column_wind_[c][2]);
  }
}

// The springs whose first node is in rows [band.begin, band.end), family by family, as one run
// of consecutive first nodes a (far node a + offset): the runs are long, so the kernel spends its
// time in full vectors. Where a row's far node does not exist (past the left or right edge) the
// run computes a spring across the wrap; those slots are set back to 0 after it.
template <typename Real>
void ForceEvaluator<Real>::SpringBand(const ClothModel<Real>& model, const ClothState<Real>& state,
                                      RowBand band) {
  const int cols = model.cols, pad = Padding(cols);
  for (size_t f = 0; f < model.families.size(); ++f) {
    const SpringFamily<Real>& family = model.families[f];
    const int offset = family.dr * cols + family.dc;
    const int last_row = std::min(band.end, model.rows - family.dr);  // rows with springs: below
    const int begin = band.begin * cols, end = std::min(last_row * cols, model.num_nodes() - offset);
    if (begin >= end) continue;
    NodeForces<Real>& out = spring_[f];
    SpringKernel(state.x.data(), state.y.data(), state.z.data(), state.vx.data(), state.vy.data(),
                 state.vz.data(), out.x.data() + pad, out.y.data() + pad, out.z.data() + pad, begin, end,
                 offset, family.stiffness, family.compression_stiffness, family.damping, family.rest_length);
    for (int r = band.begin; r < last_row; ++r) {
      ZeroColumns(&out, pad + r * cols, 0, family.first_col());
      ZeroColumns(&out, pad + r * cols, family.end_col(cols), cols);
    }
  }
}

// The two triangles of each cell in rows [band.begin, band.end), as one run of cells a (the
// cell's top-left node): upper (a, a + cols, a + 1) and lower (a + cols, a + cols + 1, a + 1).
// The last column has no cells; the run computes junk there and sets it back to 0.
template <typename Real>
void ForceEvaluator<Real>::WindBand(const ClothModel<Real>& model, const SimParams& params,
                                    const ClothState<Real>& state, RowBand band) {
  const int cols = model.cols, pad = Padding(cols);
  const int last_row = std::min(band.end, model.rows - 1);  // rows of cells
  const int begin = band.begin * cols, end = std::min(last_row * cols, model.num_nodes() - cols - 1);
  if (begin >= end) return;
  for (int r = band.begin; r < last_row; ++r) {  // each cell's wind: its column's sample
    std::copy(column_wind_x_.begin(), column_wind_x_.end(), wind_x_.begin() + r * cols);
    std::copy(column_wind_y_.begin(), column_wind_y_.end(), wind_y_.begin() + r * cols);
    std::copy(column_wind_z_.begin(), column_wind_z_.end(), wind_z_.begin() + r * cols);
  }
  const Real share = Real(params.forces.wind_coefficient / 6.0);
  const Real relative = params.relative_wind ? Real(1) : Real(0);
  const struct {
    NodeForces<Real>* out;
    int p;     ///< the first corner's offset from the cell's top-left node
    int q, s;  ///< the other corners' offsets from the first
  } triangles[2] = {{&upper_, 0, cols, 1}, {&lower_, cols, 1, 1 - cols}};
  for (const auto& triangle : triangles) {
    NodeForces<Real>& out = *triangle.out;
    WindKernel(state.x.data(), state.y.data(), state.z.data(), state.vx.data(), state.vy.data(),
               state.vz.data(), wind_x_.data(), wind_y_.data(), wind_z_.data(), out.x.data() + pad,
               out.y.data() + pad, out.z.data() + pad, begin, end, triangle.p, triangle.q, triangle.s, share,
               relative);
    for (int r = band.begin; r < last_row; ++r) ZeroColumns(&out, pad + r * cols, cols - 1, cols);
  }
}

// The curvature k = L (x + beta v) of the band's nodes, per coordinate.
template <typename Real>
void ForceEvaluator<Real>::CurvatureBand(const ClothModel<Real>& model, const ClothState<Real>& state,
                                         RowBand band) {
  const int pad = Padding(model.cols);
  CurvatureRows(model, state.x.data(), state.vx.data(), band.begin, band.end, curvature_.x.data() + pad);
  CurvatureRows(model, state.y.data(), state.vy.data(), band.begin, band.end, curvature_.y.data() + pad);
  CurvatureRows(model, state.z.data(), state.vz.data(), band.begin, band.end, curvature_.z.data() + pad);
}

// The bending force -B A L k of the band's nodes, once every band's curvature is in.
template <typename Real>
void ForceEvaluator<Real>::BendingBand(const ClothModel<Real>& model, RowBand band) {
  const int pad = Padding(model.cols);
  BendingForceRows(model, curvature_.x.data() + pad, band.begin, band.end, bending_.x.data() + pad);
  BendingForceRows(model, curvature_.y.data() + pad, band.begin, band.end, bending_.y.data() + pad);
  BendingForceRows(model, curvature_.z.data() + pad, band.begin, band.end, bending_.z.data() + pad);
}

// Every node of the band sums, in a fixed order: gravity and friction, its springs (as first node
// +f, as far node -f), its up to six triangles' wind shares, then its bending.
template <typename Real>
void ForceEvaluator<Real>::GatherBand(const ClothModel<Real>& model, const SimParams& params,
                                      const ClothState<Real>& state, RowBand band, ForceTerms terms,
                                      NodeForces<Real>* forces) const {
  const int cols = model.cols, first = band.begin * cols, count = (band.end - band.begin) * cols;
  GatherSources<Real> sources;
  int k = 0;
  // The next source is g read at slot (node - shift): the band's first node's value is there.
  const auto add = [&](const NodeForces<Real>& g, int shift) {
    const size_t start = Padding(cols) + first - shift;
    sources.x[k] = g.x.data() + start;
    sources.y[k] = g.y.data() + start;
    sources.z[k++] = g.z.data() + start;
  };
  const bool springs = Includes(terms, ForceTerms::kSprings);
  for (size_t f = 0; springs && f < model.families.size(); ++f) {
    const SpringFamily<Real>& family = model.families[f];
    add(spring_[f], 0);                             // as the first node: + f
    add(spring_[f], family.dr * cols + family.dc);  // as the far node: - f
  }
  while (k < 2 * kMaxSpringFamilies) {  // families absent: zeros
    sources.x[k] = sources.y[k] = sources.z[k] = zero_.data();
    ++k;
  }
  // Triangles touching node (r, c): upper of cells (r, c) (r-1, c) (r, c-1);
  // lower of cells (r-1, c) (r-1, c-1) (r, c-1). Without wind: zeros.
  if (Includes(terms, ForceTerms::kWind)) {
    add(upper_, 0);
    add(upper_, cols);
    add(upper_, 1);
    add(lower_, cols);
    add(lower_, cols + 1);
    add(lower_, 1);
  }
  while (k < kGatherSources - 1) {
    sources.x[k] = sources.y[k] = sources.z[k] = zero_.data();
    ++k;
  }
  if (Bends(model, terms)) add(bending_, 0);
  while (k < kGatherSources) {
    sources.x[k] = sources.y[k] = sources.z[k] = zero_.data();
    ++k;
  }
  const double gravity = Includes(terms, ForceTerms::kGravity) ? params.forces.gravity : 0.0;
  const double friction = Includes(terms, ForceTerms::kFriction) ? AirFriction(params) : 0.0;
  GatherKernel(sources, model.mass.data() + first, state.vx.data() + first, state.vy.data() + first,
               state.vz.data() + first, Real(gravity), Real(friction), forces->x.data() + first,
               forces->y.data() + first, forces->z.data() + first, count);
}

template <typename Real>
void ForceEvaluator<Real>::Evaluate(const ClothModel<Real>& model, const SimParams& params,
                                    const WindField& wind, const ClothState<Real>& state, double t,
                                    NodeForces<Real>* forces, ForceTerms terms,
                                    const std::function<void(int)>& after_row) {
  Resize(model);
  if (Includes(terms, ForceTerms::kWind)) SampleWind(model, wind, t);
  forces->x.resize(model.num_nodes());
  forces->y.resize(model.num_nodes());
  forces->z.resize(model.num_nodes());
  // The springs and faces of every band of rows; then each band gathers, and after_row runs on
  // each of its rows. A band writes only its own rows' slots, so the bands may run in any order.
  const int bands = BandCount(model.rows, params.threads);
  const bool bends = Bends(model, terms);
  ParallelFor(bands, params.threads, [&](int b) {
    const RowBand band = BandOf(model.rows, b, bands);
    if (Includes(terms, ForceTerms::kSprings)) SpringBand(model, state, band);
    if (Includes(terms, ForceTerms::kWind)) WindBand(model, params, state, band);
    if (bends) CurvatureBand(model, state, band);
  });
  ParallelFor(bands, params.threads, [&](int b) {
    const RowBand band = BandOf(model.rows, b, bands);
    if (bends) BendingBand(model, band);
    GatherBand(model, params, state, band, terms, forces);
    if (after_row) {
      for (int r = band.begin; r < band.end; ++r) after_row(r);
    }
  });
}

template class ForceEvaluator<float>;
template class ForceEvaluator<double>;

}  // namespace flagsim::sim
