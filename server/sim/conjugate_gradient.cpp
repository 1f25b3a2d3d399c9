#include "server/sim/conjugate_gradient.hpp"

#include <algorithm>
#include <cmath>

#include "server/parallel/worker_pool.hpp"

namespace flagsim::sim {
namespace {

constexpr int kLanes = 8;

/// a . b over nodes [begin, end): kLanes interleaved partial sums, then the lanes in order.
template <typename Real>
Real Dot(const NodeVectors<Real>& a, const NodeVectors<Real>& b, int begin, int end) {
  Real lane[kLanes] = {};
  int i = begin;
  for (; i + kLanes <= end; i += kLanes) {
    for (int k = 0; k < kLanes; ++k) {
      lane[k] += a.x[i + k] * b.x[i + k] + a.y[i + k] * b.y[i + k] + a.z[i + k] * b.z[i + k];
    }
  }
  for (int k = 0; i < end; ++i, ++k) lane[k] += a.x[i] * b.x[i] + a.y[i] * b.y[i] + a.z[i] * b.z[i];
  Real sum = 0;
  for (Real value : lane) sum += value;
  return sum;
}

template <typename Real>
Real SumInOrder(const std::vector<Real>& values) {
  Real sum = 0;
  for (Real value : values) sum += value;
  return sum;
}

/// y[i] = alpha x[i] + beta y[i] over nodes [begin, end).
template <typename Real>
void Combine(Real alpha, const NodeVectors<Real>& x, Real beta, NodeVectors<Real>* y, int begin, int end) {
  for (int i = begin; i < end; ++i) {
    y->x[i] = alpha * x.x[i] + beta * y->x[i];
    y->y[i] = alpha * x.y[i] + beta * y->y[i];
    y->z[i] = alpha * x.z[i] + beta * y->z[i];
  }
}

/// y[i] = x[i] over nodes [begin, end).
template <typename Real>
void Copy(const NodeVectors<Real>& x, NodeVectors<Real>* y, int begin, int end) {
  std::copy(x.x.begin() + begin, x.x.begin() + end, y->x.begin() + begin);
  std::copy(x.y.begin() + begin, x.y.begin() + end, y->y.begin() + begin);
  std::copy(x.z.begin() + begin, x.z.begin() + end, y->z.begin() + begin);
}

}  // namespace

template <typename Real>
SolveReport ConjugateGradient<Real>::Solve(const SpringJacobian<Real>& system, const NodeVectors<Real>& b,
                                           double tolerance, int max_iterations, int threads,
                                           NodeVectors<Real>* x) {
  const int rows = system.rows(), cols = system.cols();
  for (NodeVectors<Real>* vectors : {&residual_, &preconditioned_, &direction_, &product_, x}) {
    vectors->Resize(rows * cols);
  }
  for (std::vector<Real>* sums : {&row_bb_, &row_rz_, &row_rr_, &row_pq_}) sums->resize(rows);
  const Real tolerance_squared = Real(tolerance * tolerance);
  SolveReport report;
  // Rows in parallel; the sums of the row sums in order on this thread, so they are the same at
  // any thread count.
  ParallelFor(rows, threads, [&](int r) {  // r = b - A x, z = P^-1 r, p = z
    const int begin = r * cols, end = begin + cols;
    system.Multiply(*x, r, &product_);
    for (int i = begin; i < end; ++i) {
      residual_.x[i] = b.x[i] - product_.x[i];
      residual_.y[i] = b.y[i] - product_.y[i];
      residual_.z[i] = b.z[i] - product_.z[i];
    }
    system.Precondition(residual_, r, &preconditioned_);
    Copy(preconditioned_, &direction_, begin, end);
    row_bb_[r] = Dot(b, b, begin, end);
    row_rz_[r] = Dot(residual_, preconditioned_, begin, end);
    row_rr_[r] = Dot(residual_, residual_, begin, end);
  });
  const Real bb = SumInOrder(row_bb_);
  Real rz = SumInOrder(row_rz_), rr = SumInOrder(row_rr_);
  if (bb == Real(0)) {
    ParallelFor(rows, threads, [&](int r) { Copy(b, x, r * cols, (r + 1) * cols); });  // b = 0, so x = 0
    rr = 0;
  }
  int iterations = 0;
  for (; rr > tolerance_squared * bb && iterations < max_iterations; ++iterations) {
    ParallelFor(rows, threads, [&](int r) {  // q = A p
      system.Multiply(direction_, r, &product_);
      row_pq_[r] = Dot(direction_, product_, r * cols, (r + 1) * cols);
    });
    const Real alpha = rz / SumInOrder(row_pq_);
    ParallelFor(rows, threads, [&](int r) {  // x += alpha p, r -= alpha q, z = P^-1 r
      const int begin = r * cols, end = begin + cols;
      Combine(alpha, direction_, Real(1), x, begin, end);
      Combine(-alpha, product_, Real(1), &residual_, begin, end);
      system.Precondition(residual_, r, &preconditioned_);
      row_rz_[r] = Dot(residual_, preconditioned_, begin, end);
      row_rr_[r] = Dot(residual_, residual_, begin, end);
    });
    const Real rz_next = SumInOrder(row_rz_);
    const Real beta = rz_next / rz;
    rz = rz_next;
    rr = SumInOrder(row_rr_);
    ParallelFor(rows, threads, [&](int r) {
      Combine(Real(1), preconditioned_, beta, &direction_, r * cols, (r + 1) * cols);
    });
  }
  report.iterations = iterations;
  report.relative_residual = bb > 0 ? std::sqrt(double(rr) / double(bb)) : 0.0;
  return report;
}

template class ConjugateGradient<float>;
template class ConjugateGradient<double>;

}  // namespace flagsim::sim
