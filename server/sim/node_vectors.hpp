// A 3-vector per node, structure of arrays like the state: velocity changes, displacements,
// right-hand sides and the solvers' work vectors.
#pragma once

#include <vector>

namespace flagsim::sim {

template <typename Real>
struct NodeVectors {
  std::vector<Real> x, y, z;

  /// n nodes; new entries are zero, existing ones keep their values.
  void Resize(int n) {
    x.resize(n, Real(0));
    y.resize(n, Real(0));
    z.resize(n, Real(0));
  }
  void SetZero() {
    x.assign(x.size(), Real(0));
    y.assign(y.size(), Real(0));
    z.assign(z.size(), Real(0));
  }
};

}  // namespace flagsim::sim
