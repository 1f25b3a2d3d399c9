#include "lab/shape_statistics.hpp"

#include <algorithm>
#include <cmath>

#include "server/sim/bending.hpp"

namespace flagsim::lab {
namespace {

using Vector = std::array<double, 3>;

template <typename Real>
Vector At(const sim::ClothState<Real>& state, int i) {
  return {double(state.x[i]), double(state.y[i]), double(state.z[i])};
}

Vector Cross(const Vector& a, const Vector& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// Student's t at 97.5% for n degrees of freedom (n >= 1), from the table; 1.96 beyond 30.
double StudentT975(int n) {
  static const double kTable[] = {12.706, 4.303, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201,
                                  2.179,  2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080,
                                  2.074,  2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042, 2.042};
  return n <= 30 ? kTable[n - 1] : 1.96;
}

double Mean(const std::vector<double>& values) {
  double sum = 0;
  for (double v : values) sum += v;
  return values.empty() ? 0.0 : sum / values.size();
}

/// The normal curvature (L x) . n at every node: 0 at boundary nodes.
template <typename Real>
std::vector<double> NormalCurvature(const sim::ClothModel<Real>& model, const sim::ClothState<Real>& state,
                                    double* mean_curvature) {
  std::vector<double> normal_curvature(model.num_nodes(), 0.0);
  double sum = 0;
  int count = 0;
  for (int r = 1; r + 1 < model.rows; ++r) {
    for (int c = 1; c + 1 < model.cols; ++c) {
      const sim::BendingStencil s = sim::StencilOf(model, r, c);
      const Vector laplacian = sim::CurvatureAt(model, state.x, state.y, state.z, r, c);
      Vector along, down;
      for (int k = 0; k < 3; ++k) {
        along[k] = At(state, s.nodes[2])[k] - At(state, s.nodes[1])[k];
        down[k] = At(state, s.nodes[4])[k] - At(state, s.nodes[3])[k];
      }
      Vector normal = Cross(along, down);
      const double length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
      const double size =
          std::sqrt(laplacian[0] * laplacian[0] + laplacian[1] * laplacian[1] + laplacian[2] * laplacian[2]);
      sum += size;
      ++count;
      if (length > 0) {
        normal_curvature[s.nodes[0]] =
            (laplacian[0] * normal[0] + laplacian[1] * normal[1] + laplacian[2] * normal[2]) / length;
      }
    }
  }
  *mean_curvature = count > 0 ? sum / count : 0.0;
  return normal_curvature;
}

}  // namespace

int SchmittCrossings(const std::vector<double>& values, double centre, double band) {
  int crossings = 0, side = 0;  // side: -1 below the band, +1 above, 0 not yet either
  for (double v : values) {
    const int now = v > centre + band ? 1 : v < centre - band ? -1 : 0;
    if (now != 0 && side != 0 && now != side) ++crossings;
    if (now != 0) side = now;
  }
  return crossings;
}

template <typename Real>
ShapeSample SampleShape(const sim::ClothModel<Real>& model, const sim::ClothState<Real>& state) {
  ShapeSample sample;
  sample.t = state.time;
  for (int r = 0; r < model.rows; ++r) {
    const Vector p = At(state, model.index(r, model.cols - 1));
    for (int k = 0; k < 3; ++k) sample.fly[k] += p[k] / model.rows;
  }
  const std::vector<double> normal_curvature = NormalCurvature(model, state, &sample.curvature);
  const double band = 0.25 * sample.curvature;
  std::vector<double> line;
  for (int r = 1; r + 1 < model.rows; ++r) {  // along the interior rows
    line.clear();
    for (int c = 1; c + 1 < model.cols; ++c) line.push_back(normal_curvature[model.index(r, c)]);
    sample.folds_along += SchmittCrossings(line, 0.0, band);
    sample.length_along += (model.cols - 3) * double(model.dx);
  }
  for (int c = 1; c + 1 < model.cols; ++c) {  // down the interior columns
    line.clear();
    for (int r = 1; r + 1 < model.rows; ++r) line.push_back(normal_curvature[model.index(r, c)]);
    sample.folds_down += SchmittCrossings(line, 0.0, band);
    sample.length_down += (model.rows - 3) * double(model.dy);
  }
  return sample;
}

Estimate BatchEstimate(const std::vector<double>& batch_means) {
  Estimate estimate;
  const int n = static_cast<int>(batch_means.size());
  estimate.mean = Mean(batch_means);
  if (n < 2) return estimate;
  double square = 0;
  for (double v : batch_means) square += (v - estimate.mean) * (v - estimate.mean);
  estimate.half_width = StudentT975(n - 1) * std::sqrt(square / (n - 1) / n);
  return estimate;
}

ShapeStatistics SummariseShape(const std::vector<ShapeSample>& samples, int batches) {
  ShapeStatistics statistics;
  const int per_batch = batches > 0 ? static_cast<int>(samples.size()) / batches : 0;
  if (per_batch < 2) return statistics;
  statistics.batches = batches;
  // The fly edge's time-averaged position, and the horizontal direction across it: the flutter's.
  Vector centre{0, 0, 0};
  for (const ShapeSample& s : samples) {
    for (int k = 0; k < 3; ++k) centre[k] += s.fly[k] / samples.size();
  }
  const double horizontal = std::hypot(centre[0], centre[2]);
  const Vector across = horizontal > 0 ? Vector{-centre[2] / horizontal, 0, centre[0] / horizontal} : Vector{0, 0, 1};
  std::vector<double> reach, height, spread, curvature, fold_along, fold_down, flutter;
  for (int b = 0; b < batches; ++b) {
    const auto first = samples.begin() + b * per_batch, last = first + per_batch;
    std::vector<double> r, h, d, k, lateral;
    double folds_along = 0, length_along = 0, folds_down = 0, length_down = 0;
    for (auto s = first; s != last; ++s) {
      r.push_back(std::hypot(s->fly[0], s->fly[2]));
      h.push_back(s->fly[1]);
      double distance = 0;
      for (int i = 0; i < 3; ++i) distance += (s->fly[i] - centre[i]) * (s->fly[i] - centre[i]);
      d.push_back(distance);
      k.push_back(s->curvature);
      lateral.push_back((s->fly[0] - centre[0]) * across[0] + (s->fly[2] - centre[2]) * across[2]);
      folds_along += s->folds_along;
      length_along += s->length_along;
      folds_down += s->folds_down;
      length_down += s->length_down;
    }
    reach.push_back(Mean(r));
    height.push_back(Mean(h));
    spread.push_back(std::sqrt(Mean(d)));
    curvature.push_back(Mean(k));
    fold_along.push_back(folds_along > 0 ? 2 * length_along / folds_along : 0.0);
    fold_down.push_back(folds_down > 0 ? 2 * length_down / folds_down : 0.0);
    double lateral_square = 0;
    for (double v : lateral) lateral_square += v * v;
    const double band = 0.25 * std::sqrt(lateral_square / lateral.size());
    const double duration = (last - 1)->t - first->t;
    flutter.push_back(duration > 0 ? 0.5 * SchmittCrossings(lateral, 0.0, band) / duration : 0.0);
  }
  statistics.reach = BatchEstimate(reach);
  statistics.height = BatchEstimate(height);
  statistics.spread = BatchEstimate(spread);
  statistics.curvature = BatchEstimate(curvature);
  statistics.fold_along = BatchEstimate(fold_along);
  statistics.fold_down = BatchEstimate(fold_down);
  statistics.flutter = BatchEstimate(flutter);
  return statistics;
}

template ShapeSample SampleShape<float>(const sim::ClothModel<float>&, const sim::ClothState<float>&);
template ShapeSample SampleShape<double>(const sim::ClothModel<double>&, const sim::ClothState<double>&);

}  // namespace flagsim::lab
