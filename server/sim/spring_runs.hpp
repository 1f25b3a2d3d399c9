// The springs touching one grid row, as runs of consecutive nodes: what a row-parallel gather
// loops over. Per-spring quantities are stored per family, indexed by the spring's first node
// (as in forces.cpp), so node a of a run finds its spring at a + spring_shift and the spring's
// other node at a + other_shift:
//   a is the first node of springs (r, c) -> (r + dr, c + dc): spring_shift 0, other_shift +offset
//   a is the far node of springs (r - dr, c - dc) -> (r, c):   spring_shift = other_shift = -offset
// with offset = dr cols + dc. Runs come family by family, first-node run before far-node run, so
// a gather that follows them sums every node's springs in one fixed order.
#pragma once

#include "server/sim/cloth_model.hpp"

namespace flagsim::sim {

struct SpringRun {
  int family = 0;
  int begin = 0, end = 0;  ///< nodes [begin, end) of the row
  int spring_shift = 0;    ///< the node's spring is stored at a + spring_shift
  int other_shift = 0;     ///< the spring's other node is a + other_shift
  bool first = true;       ///< the nodes are the springs' first nodes (else their far nodes)
};

/// Calls visit(run) for every run of springs touching row r, in the fixed order above.
template <typename Real, typename Visit>
void ForEachSpringRun(const ClothModel<Real>& model, int r, Visit&& visit) {
  const int cols = model.cols, row = r * cols;
  for (int f = 0; f < static_cast<int>(model.families.size()); ++f) {
    const SpringFamily<Real>& family = model.families[f];
    const int offset = family.dr * cols + family.dc;
    const int first = family.first_col(), end = family.end_col(cols);
    if (r + family.dr < model.rows) visit(SpringRun{f, row + first, row + end, 0, offset, true});
    if (r - family.dr >= 0) {
      visit(SpringRun{f, row + first + family.dc, row + end + family.dc, -offset, -offset, false});
    }
  }
}

}  // namespace flagsim::sim
