#include "server/sim/resample.hpp"

#include <algorithm>
#include <cmath>

namespace flagsim::sim {
namespace {

/// Where coordinate s in [0, 1] falls on a line of `count` nodes: the cell's first node and the
/// fraction across it. A node of the line is hit exactly (fraction 0) when s names it exactly.
struct Cell {
  int first = 0;
  double fraction = 0;
};
Cell CellAt(int index, int new_count, int old_count) {
  // s = index / (new_count - 1); position = s (old_count - 1), as a ratio of integers so that
  // coinciding nodes come out exact.
  const long long numerator = static_cast<long long>(index) * (old_count - 1);
  const long long denominator = new_count - 1;
  Cell cell;
  cell.first = static_cast<int>(numerator / denominator);
  cell.fraction = double(numerator % denominator) / double(denominator);
  if (cell.first >= old_count - 1) {  // the last node: the cell before it, all the way across
    cell.first = std::max(0, old_count - 2);
    cell.fraction = old_count > 1 ? 1.0 : 0.0;
  }
  return cell;
}

/// Bilinear in the cell with corners a (top left), b (top right), c (bottom left), d.
template <typename Real>
Real Bilinear(const std::vector<Real>& values, int a, int b, int c, int d, double across, double down) {
  if (across == 0 && down == 0) return values[a];  // on a node: exact
  const double top = (1 - across) * double(values[a]) + across * double(values[b]);
  const double bottom = (1 - across) * double(values[c]) + across * double(values[d]);
  return Real((1 - down) * top + down * bottom);
}

}  // namespace

template <typename Real>
ClothState<Real> Resample(const ClothModel<Real>& from, const ClothState<Real>& state,
                               const ClothModel<Real>& to) {
  ClothState<Real> out = RestState(to);
  out.time = state.time;
  out.step = state.step;
  for (int r = 0; r < to.rows; ++r) {
    const Cell row = CellAt(r, to.rows, from.rows);
    for (int c = 0; c < to.cols; ++c) {
      const int i = to.index(r, c);
      if (to.pinned(i)) continue;  // on the pole where the new model puts it, at rest
      const Cell column = CellAt(c, to.cols, from.cols);
      const int a = from.index(row.first, column.first);
      const int b = column.first + 1 < from.cols ? a + 1 : a;
      const int below = row.first + 1 < from.rows ? from.cols : 0;
      const auto sample = [&](const std::vector<Real>& values) {
        return Bilinear(values, a, b, a + below, b + below, column.fraction, row.fraction);
      };
      out.x[i] = sample(state.x);
      out.y[i] = sample(state.y);
      out.z[i] = sample(state.z);
      out.vx[i] = sample(state.vx);
      out.vy[i] = sample(state.vy);
      out.vz[i] = sample(state.vz);
    }
  }
  return out;
}

template ClothState<float> Resample<float>(const ClothModel<float>&, const ClothState<float>&,
                                                const ClothModel<float>&);
template ClothState<double> Resample<double>(const ClothModel<double>&, const ClothState<double>&,
                                                  const ClothModel<double>&);

}  // namespace flagsim::sim
