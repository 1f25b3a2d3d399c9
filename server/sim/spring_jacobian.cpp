#include "server/sim/spring_jacobian.hpp"

#include <algorithm>
#include <cmath>

#include "server/parallel/worker_pool.hpp"
#include "server/sim/bending.hpp"
#include "server/sim/spring_runs.hpp"

namespace flagsim::sim {
namespace {

// Every array is a __restrict parameter so that the loops over a grid row vectorise.

/// Blocks of springs a -> a + offset for a in [begin, end), from h^2 k and h c; h^2 k is the
/// stretched spring's, or the compressed one's when |d| < L (the regime forces.cpp's law is in).
template <typename Real>
void BlockKernel(const Real* __restrict x, const Real* __restrict y, const Real* __restrict z,
                 Real* __restrict ux, Real* __restrict uy, Real* __restrict uz, Real* __restrict iso,
                 Real* __restrict axial, Real* __restrict axial_stiffness, int begin, int end, int offset,
                 Real h2k_stretched, Real h2k_compressed, Real hc, Real rest) {
  for (int a = begin; a < end; ++a) {
    const int b = a + offset;
    const Real dx = x[b] - x[a], dy = y[b] - y[a], dz = z[b] - z[a];
    const Real length_squared = dx * dx + dy * dy + dz * dz;
    const Real inverse = Real(1) / std::max(std::sqrt(length_squared), Real(kShortestSpring));
    const Real h2k = length_squared * inverse < rest ? h2k_compressed : h2k_stretched;
    const Real alpha = std::max(Real(0), Real(1) - rest * inverse);
    ux[a] = dx * inverse;
    uy[a] = dy * inverse;
    uz[a] = dz * inverse;
    iso[a] = h2k * alpha;
    axial_stiffness[a] = h2k * (Real(1) - alpha);
    axial[a] = axial_stiffness[a] + hc;
  }
}

/// out[a] += (iso I + axial u u^T)[s] (p[a] - p[o]), s = a + spring_shift, o = a + other_shift.
template <typename Real>
void ProductKernel(const Real* __restrict px, const Real* __restrict py, const Real* __restrict pz,
                   const Real* __restrict ux, const Real* __restrict uy, const Real* __restrict uz,
                   const Real* __restrict iso, const Real* __restrict axial, Real* __restrict outx,
                   Real* __restrict outy, Real* __restrict outz, int begin, int end, int spring_shift,
                   int other_shift) {
  for (int a = begin; a < end; ++a) {
    const int s = a + spring_shift, o = a + other_shift;
    const Real ex = px[a] - px[o], ey = py[a] - py[o], ez = pz[a] - pz[o];
    const Real along = axial[s] * (ux[s] * ex + uy[s] * ey + uz[s] * ez);
    outx[a] += iso[s] * ex + along * ux[s];
    outy[a] += iso[s] * ey + along * uy[s];
    outz[a] += iso[s] * ez + along * uz[s];
  }
}

/// diagonal[a] += (iso I + axial u u^T)[a + spring_shift] for a in [begin, end).
template <typename Real>
void DiagonalKernel(const Real* __restrict ux, const Real* __restrict uy, const Real* __restrict uz,
                    const Real* __restrict iso, const Real* __restrict axial, Real* __restrict xx,
                    Real* __restrict xy, Real* __restrict xz, Real* __restrict yy, Real* __restrict yz,
                    Real* __restrict zz, int begin, int end, int spring_shift) {
  for (int a = begin; a < end; ++a) {
    const int s = a + spring_shift;
    xx[a] += iso[s] + axial[s] * ux[s] * ux[s];
    xy[a] += axial[s] * ux[s] * uy[s];
    xz[a] += axial[s] * ux[s] * uz[s];
    yy[a] += iso[s] + axial[s] * uy[s] * uy[s];
    yz[a] += axial[s] * uy[s] * uz[s];
    zz[a] += iso[s] + axial[s] * uz[s] * uz[s];
  }
}

/// Each symmetric block [a, a + n) replaced by its inverse (adjugate over determinant) times
/// keep[a], which is 0 or 1.
template <typename Real>
void InvertKernel(Real* __restrict xx, Real* __restrict xy, Real* __restrict xz, Real* __restrict yy,
                  Real* __restrict yz, Real* __restrict zz, const Real* __restrict keep, int n) {
  for (int a = 0; a < n; ++a) {
    const Real cxx = yy[a] * zz[a] - yz[a] * yz[a], cxy = xz[a] * yz[a] - xy[a] * zz[a],
               cxz = xy[a] * yz[a] - xz[a] * yy[a], cyy = xx[a] * zz[a] - xz[a] * xz[a],
               cyz = xy[a] * xz[a] - xx[a] * yz[a], czz = xx[a] * yy[a] - xy[a] * xy[a];
    const Real scale = keep[a] / (xx[a] * cxx + xy[a] * cxy + xz[a] * cxz);
    xx[a] = scale * cxx;
    xy[a] = scale * cxy;
    xz[a] = scale * cxz;
    yy[a] = scale * cyy;
    yz[a] = scale * cyz;
    zz[a] = scale * czz;
  }
}

}  // namespace

template <typename Real>
void SpringJacobian<Real>::Resize() {
  const size_t n = model_->num_nodes();
  blocks_.resize(model_->families.size());
  for (FamilyBlocks& family : blocks_) {
    for (std::vector<Real>* values :
         {&family.ux, &family.uy, &family.uz, &family.iso, &family.axial, &family.axial_stiffness}) {
      values->resize(n);
    }
  }
  NodeBlocks& d = inverse_diagonal_;
  for (std::vector<Real>* values : {&d.xx, &d.xy, &d.xz, &d.yy, &d.yz, &d.zz}) values->resize(n);
  scaled_mass_.resize(n);
  free_.resize(n);
}

template <typename Real>
void SpringJacobian<Real>::Assemble(const ClothModel<Real>& model, const ClothState<Real>& state,
                                    const NodeForces<Real>& forces, double h, double friction, int threads,
                                    NodeVectors<Real>* rhs) {
  model_ = &model;
  h_ = Real(h);
  Resize();
  rhs->Resize(model.num_nodes());
  const Real mass_scale = Real(1 + h * friction);
  const int rows = model.rows, cols = model.cols;
  // The blocks of springs starting in each row; then each row gathers.
  ParallelFor(rows, threads, [&](int r) {
    for (int i = r * cols; i < (r + 1) * cols; ++i) {
      scaled_mass_[i] = mass_scale * model.mass[i];
      free_[i] = model.pinned(i) ? Real(0) : Real(1);
    }
    BlockRow(state, Real(h), r);
  });
  ParallelFor(rows, threads, [&](int r) {
    InverseDiagonalRow(r);
    RightHandSideRow(state, forces, Real(h), r, rhs);
  });
}

template <typename Real>
void SpringJacobian<Real>::BlockRow(const ClothState<Real>& state, Real h, int r) {
  const ClothModel<Real>& model = *model_;
  for (size_t f = 0; f < model.families.size(); ++f) {
    const SpringFamily<Real>& family = model.families[f];
    if (r + family.dr >= model.rows) continue;
    FamilyBlocks& out = blocks_[f];
    BlockKernel(state.x.data(), state.y.data(), state.z.data(), out.ux.data(), out.uy.data(), out.uz.data(),
                out.iso.data(), out.axial.data(), out.axial_stiffness.data(),
                model.index(r, family.first_col()), model.index(r, family.end_col(model.cols)),
                family.dr * model.cols + family.dc, h * h * family.stiffness,
                h * h * family.compression_stiffness, h * family.damping, family.rest_length);
  }
}

template <typename Real>
void SpringJacobian<Real>::InverseDiagonalRow(int r) {
  const int row = r * model_->cols, cols = model_->cols;
  NodeBlocks& d = inverse_diagonal_;
  for (int i = row; i < row + cols; ++i) {
    d.xx[i] = d.yy[i] = d.zz[i] = scaled_mass_[i];
    d.xy[i] = d.xz[i] = d.yz[i] = Real(0);
  }
  const Real bending = BendingFactor();
  for (int c = 0; bending != Real(0) && c < cols; ++c) {
    const Real diagonal = bending * Real(BendingDiagonal(*model_, r, c));
    d.xx[row + c] += diagonal;
    d.yy[row + c] += diagonal;
    d.zz[row + c] += diagonal;
  }
  ForEachSpringRun(*model_, r, [&](const SpringRun& run) {
    const FamilyBlocks& b = blocks_[run.family];
    DiagonalKernel(b.ux.data(), b.uy.data(), b.uz.data(), b.iso.data(), b.axial.data(), d.xx.data(),
                   d.xy.data(), d.xz.data(), d.yy.data(), d.yz.data(), d.zz.data(), run.begin, run.end,
                   run.spring_shift);
  });
  InvertKernel(d.xx.data() + row, d.xy.data() + row, d.xz.data() + row, d.yy.data() + row, d.yz.data() + row,
               d.zz.data() + row, free_.data() + row, cols);
}

template <typename Real>
void SpringJacobian<Real>::RightHandSideRow(const ClothState<Real>& state, const NodeForces<Real>& forces,
                                            Real h, int r, NodeVectors<Real>* rhs) const {
  const int row = r * model_->cols, end = row + model_->cols;
  std::fill(rhs->x.begin() + row, rhs->x.begin() + end, Real(0));
  std::fill(rhs->y.begin() + row, rhs->y.begin() + end, Real(0));
  std::fill(rhs->z.begin() + row, rhs->z.begin() + end, Real(0));
  AddSpringProducts(state.vx.data(), state.vy.data(), state.vz.data(), r, &FamilyBlocks::axial_stiffness,
                    rhs);
  AddBendingProducts(state.vx.data(), state.vy.data(), state.vz.data(), r, h * h, rhs);
  for (int i = row; i < end; ++i) {
    rhs->x[i] = free_[i] * (h * forces.x[i] - rhs->x[i]);
    rhs->y[i] = free_[i] * (h * forces.y[i] - rhs->y[i]);
    rhs->z[i] = free_[i] * (h * forces.z[i] - rhs->z[i]);
  }
}

template <typename Real>
void SpringJacobian<Real>::AddSpringProducts(const Real* px, const Real* py, const Real* pz, int r,
                                             std::vector<Real> FamilyBlocks::*axial,
                                             NodeVectors<Real>* out) const {
  ForEachSpringRun(*model_, r, [&](const SpringRun& run) {
    const FamilyBlocks& b = blocks_[run.family];
    ProductKernel(px, py, pz, b.ux.data(), b.uy.data(), b.uz.data(), b.iso.data(), (b.*axial).data(),
                  out->x.data(), out->y.data(), out->z.data(), run.begin, run.end, run.spring_shift,
                  run.other_shift);
  });
}

template <typename Real>
void SpringJacobian<Real>::AddBendingProducts(const Real* px, const Real* py, const Real* pz, int r, Real scale,
                                              NodeVectors<Real>* out) const {
  if (scale == Real(0) || model_->bending_stiffness == Real(0)) return;
  const int row = r * model_->cols;
  for (int c = 0; c < model_->cols; ++c) {
    out->x[row + c] += scale * BendingProductAt(*model_, px, r, c);
    out->y[row + c] += scale * BendingProductAt(*model_, py, r, c);
    out->z[row + c] += scale * BendingProductAt(*model_, pz, r, c);
  }
}

template <typename Real>
void SpringJacobian<Real>::Multiply(const NodeVectors<Real>& p, int r, NodeVectors<Real>* out) const {
  const int row = r * model_->cols, end = row + model_->cols;
  for (int i = row; i < end; ++i) {
    out->x[i] = scaled_mass_[i] * p.x[i];
    out->y[i] = scaled_mass_[i] * p.y[i];
    out->z[i] = scaled_mass_[i] * p.z[i];
  }
  AddSpringProducts(p.x.data(), p.y.data(), p.z.data(), r, &FamilyBlocks::axial, out);
  AddBendingProducts(p.x.data(), p.y.data(), p.z.data(), r, BendingFactor(), out);
  for (int i = row; i < end; ++i) {
    out->x[i] *= free_[i];
    out->y[i] *= free_[i];
    out->z[i] *= free_[i];
  }
}

template <typename Real>
void SpringJacobian<Real>::Precondition(const NodeVectors<Real>& residual, int r,
                                        NodeVectors<Real>* out) const {
  const NodeBlocks& d = inverse_diagonal_;
  const int row = r * model_->cols, end = row + model_->cols;
  for (int i = row; i < end; ++i) {
    const Real x = residual.x[i], y = residual.y[i], z = residual.z[i];
    out->x[i] = d.xx[i] * x + d.xy[i] * y + d.xz[i] * z;
    out->y[i] = d.xy[i] * x + d.yy[i] * y + d.yz[i] * z;
    out->z[i] = d.xz[i] * x + d.yz[i] * y + d.zz[i] * z;
  }
}

template <typename Real>
void SpringJacobian<Real>::Filter(NodeVectors<Real>* v) const {
  v->Resize(model_->num_nodes());
  for (size_t i = 0; i < free_.size(); ++i) {
    v->x[i] *= free_[i];
    v->y[i] *= free_[i];
    v->z[i] *= free_[i];
  }
}

template class SpringJacobian<float>;
template class SpringJacobian<double>;

}  // namespace flagsim::sim
