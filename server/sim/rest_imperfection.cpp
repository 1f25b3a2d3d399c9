#include "server/sim/rest_imperfection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace flagsim::sim {
namespace {

constexpr int kAlongModes = 3;          ///< m = 1..3: sin((2m - 1) pi u / 2)
constexpr int kDownModes = 3;           ///< n = 0..2: cos(n pi v)
constexpr uint64_t kSeed = 0x5eedf1a6;  ///< any fixed value: the flag's one imperfection

using Coefficients = std::array<std::array<double, kDownModes>, kAlongModes>;

/// a_mn / (m + n), a_mn uniform in [-1, 1]: std::mt19937_64's sequence is fixed by the standard,
/// and the 53 high bits make the double by hand (the standard's distributions are not portable).
Coefficients DrawCoefficients() {
  std::mt19937_64 generator(kSeed);
  Coefficients a{};
  for (int m = 0; m < kAlongModes; ++m) {
    for (int n = 0; n < kDownModes; ++n) {
      const double uniform = double(generator() >> 11) * 0x1p-53;  // [0, 1)
      a[m][n] = (2 * uniform - 1) / ((m + 1) + n);
    }
  }
  return a;
}

/// s(u, v) of rest_imperfection.hpp.
double Shape(const Coefficients& a, double u, double v) {
  double s = 0;
  for (int m = 0; m < kAlongModes; ++m) {
    const double along = std::sin((2 * m + 1) * M_PI * u / 2);
    for (int n = 0; n < kDownModes; ++n) s += a[m][n] * along * std::cos(n * M_PI * v);
  }
  return s;
}

}  // namespace

template <typename Real>
void AddRestImperfection(const SimParams& params, ClothModel<Real>* model) {
  if (params.imperfection == 0) return;
  const Coefficients a = DrawCoefficients();
  std::vector<double> shape(model->num_nodes(), 0.0);
  double largest = 0;
  for (int r = 0; r < model->rows; ++r) {
    for (int c = 0; c < model->cols; ++c) {
      const int i = model->index(r, c);
      if (model->pinned(i)) continue;
      shape[i] = Shape(a, double(c) / (model->cols - 1), double(r) / (model->rows - 1));
      largest = std::max(largest, std::abs(shape[i]));
    }
  }
  if (largest == 0) return;
  const double scale = params.imperfection / largest;
  for (int i = 0; i < model->num_nodes(); ++i) model->rest_z[i] += Real(scale * shape[i]);
}

template void AddRestImperfection<float>(const SimParams&, ClothModel<float>*);
template void AddRestImperfection<double>(const SimParams&, ClothModel<double>*);

}  // namespace flagsim::sim
