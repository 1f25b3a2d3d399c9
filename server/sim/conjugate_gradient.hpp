// Preconditioned conjugate gradient on a SpringJacobian's system A x = b (A symmetric positive
// definite on the free nodes, pinned rows filtered to zero):
//   r = b - A x,  z = P^-1 r,  p = z
//   until |r| <= tolerance |b| or max_iterations:
//     q = A p,  alpha = (r . z) / (p . q),  x += alpha p,  r -= alpha q
//     z = P^-1 r,  beta = (r . z)_new / (r . z)_old,  p = z + beta p
// One parallel region: each loop runs over grid rows; each dot product is summed per row (in
// eight fixed lanes, then the lanes in order) and then over rows in order by every thread, so
// the result is the same bit for bit at any thread count and any vector width.
#pragma once

#include <vector>

#include "server/sim/node_vectors.hpp"
#include "server/sim/spring_jacobian.hpp"

namespace flagsim::sim {

struct SolveReport {
  int iterations = 0;
  double relative_residual = 0;  ///< |r| / |b| as the iteration tracks it; 0 when b = 0
};

template <typename Real>
class ConjugateGradient {
 public:
  /// Solves A x = b, starting from *x (resized with zeros if needed); x = 0 when b = 0.
  SolveReport Solve(const SpringJacobian<Real>& system, const NodeVectors<Real>& b, double tolerance,
                    int max_iterations, int threads, NodeVectors<Real>* x);

 private:
  NodeVectors<Real> residual_, preconditioned_, direction_, product_;
  std::vector<Real> row_bb_, row_rz_, row_rr_, row_pq_;  ///< per-row partial dot products
};

}  // namespace flagsim::sim
