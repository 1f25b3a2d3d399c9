#include "server/sim/spring_laplacian.hpp"

#include "server/parallel/worker_pool.hpp"
#include "server/sim/bending.hpp"

namespace flagsim::sim {
namespace {

template <typename Real>
bool SameConstants(const std::vector<SpringFamily<Real>>& a, const std::vector<SpringFamily<Real>>& b) {
  if (a.size() != b.size()) return false;
  for (size_t f = 0; f < a.size(); ++f) {
    if (a[f].dr != b[f].dr || a[f].dc != b[f].dc || a[f].stiffness != b[f].stiffness ||
        a[f].damping != b[f].damping) {
      return false;
    }
  }
  return true;
}

/// (h^2 + h beta) B Q over the free nodes: each interior node j adds (h^2 + h beta) B A s_j s_j^T.
template <typename Real>
void AddBendingEntries(const ClothModel<Real>& model, double h, std::vector<Eigen::Triplet<Real>>* entries) {
  if (model.bending_stiffness == Real(0)) return;
  const double scale = (h * h + h * double(model.bending_damping)) * double(model.bending_stiffness) *
                       double(model.dx) * double(model.dy);
  for (int r = 1; r + 1 < model.rows; ++r) {
    for (int c = 1; c + 1 < model.cols; ++c) {
      const BendingStencil s = StencilOf(model, r, c);
      for (int a = 0; a < 5; ++a) {
        for (int b = 0; b < 5; ++b) {
          if (model.pinned(s.nodes[a]) || model.pinned(s.nodes[b])) continue;
          entries->emplace_back(s.nodes[a], s.nodes[b], Real(scale * s.weights[a] * s.weights[b]));
        }
      }
    }
  }
}

}  // namespace

template <typename Real>
bool SpringLaplacian<Real>::Current(const ClothModel<Real>& model, double h, double friction) const {
  return factorised_ && h == h_ && friction == friction_ && model.cols == cols_ && model.rows == rows_ &&
         SameConstants(model.families, families_) && model.bending_stiffness == bending_stiffness_ &&
         model.bending_damping == bending_damping_ && model.mass == mass_ &&
         model.inverse_mass == inverse_mass_;
}

template <typename Real>
void SpringLaplacian<Real>::Prepare(const ClothModel<Real>& model, double h, double friction) {
  if (Current(model, h, friction)) return;
  h_ = h;
  friction_ = friction;
  cols_ = model.cols;
  rows_ = model.rows;
  families_ = model.families;
  bending_stiffness_ = model.bending_stiffness;
  bending_damping_ = model.bending_damping;
  mass_ = model.mass;
  inverse_mass_ = model.inverse_mass;
  Factorise(model);
  factorised_ = true;
}

template <typename Real>
void SpringLaplacian<Real>::Factorise(const ClothModel<Real>& model) {
  std::vector<Eigen::Triplet<Real>> entries;
  for (int i = 0; i < model.num_nodes(); ++i) {
    entries.emplace_back(i, i, model.pinned(i) ? Real(1) : Real((1 + h_ * friction_) * model.mass[i]));
  }
  for (const SpringFamily<Real>& family : model.families) {
    const Real weight = Real(h_ * family.damping + h_ * h_ * family.stiffness);
    for (int r = 0; r + family.dr < model.rows; ++r) {
      for (int c = family.first_col(); c < family.end_col(model.cols); ++c) {
        const int a = model.index(r, c), b = model.index(r + family.dr, c + family.dc);
        const bool free_a = !model.pinned(a), free_b = !model.pinned(b);
        if (free_a) entries.emplace_back(a, a, weight);
        if (free_b) entries.emplace_back(b, b, weight);
        if (free_a && free_b) {
          entries.emplace_back(a, b, -weight);
          entries.emplace_back(b, a, -weight);
        }
      }
    }
  }
  AddBendingEntries(model, h_, &entries);
  Matrix matrix(model.num_nodes(), model.num_nodes());
  matrix.setFromTriplets(entries.begin(), entries.end());  // sums the duplicates
  factorisation_.compute(matrix);
}

template <typename Real>
void SpringLaplacian<Real>::Solve(const NodeVectors<Real>& b, int threads, NodeVectors<Real>* x) const {
  using Vector = Eigen::Matrix<Real, Eigen::Dynamic, 1>;
  const int n = static_cast<int>(b.x.size());
  x->Resize(n);
  const std::vector<Real>* from[3] = {&b.x, &b.y, &b.z};
  std::vector<Real>* to[3] = {&x->x, &x->y, &x->z};
  ParallelFor(3, threads, [&](int k) {
    Eigen::Map<Vector>(to[k]->data(), n) = factorisation_.solve(Eigen::Map<const Vector>(from[k]->data(), n));
  });
}

template class SpringLaplacian<float>;
template class SpringLaplacian<double>;

}  // namespace flagsim::sim
