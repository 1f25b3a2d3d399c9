#include "server/model/frame_defect.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace flagsim::model {
namespace {

/// The state after `steps` steps from `snapshot` with its substeps times `refine`.
sim::ClothState<float> Advance(sim::SimulationSnapshot<float> snapshot, int refine, int steps) {
  snapshot.substeps *= refine;
  sim::Simulation<float> simulation(snapshot);
  for (int i = 0; i < steps; ++i) simulation.Step();
  return simulation.state();
}

}  // namespace

int OrderOf(sim::IntegratorKind kind) {
  switch (kind) {
    case sim::IntegratorKind::kVelocityVerlet:
      return 2;
    case sim::IntegratorKind::kRk4:
      return 4;
    default:
      return 1;
  }
}

Gap ScreenGap(const render::Camera& camera, const sim::ClothState<float>& a, const sim::ClothState<float>& b) {
  const Eigen::Matrix4d clip_from_world = camera.Projection() * camera.View();
  std::vector<double> gaps(a.num_nodes());
  for (int i = 0; i < a.num_nodes(); ++i) {
    Eigen::Vector2d pa, pb;
    const bool seen = render::ToPixel(clip_from_world, camera, a.x[i], a.y[i], a.z[i], &pa) &&
                      render::ToPixel(clip_from_world, camera, b.x[i], b.y[i], b.z[i], &pb);
    const double gap = seen ? (pa - pb).norm() : std::numeric_limits<double>::infinity();
    gaps[i] = std::isnan(gap) ? std::numeric_limits<double>::infinity() : gap;
  }
  if (gaps.empty()) return {};
  const size_t rank = std::min(gaps.size() - 1, size_t(std::ceil(kDefectPercentile * gaps.size())) - 1);
  std::nth_element(gaps.begin(), gaps.begin() + rank, gaps.end());
  Gap gap;
  gap.percentile = gaps[rank];
  gap.largest = *std::max_element(gaps.begin() + rank, gaps.end());
  return gap;
}

FrameDefect MeasureFrameDefect(const sim::SimulationSnapshot<float>& snapshot, const render::Camera& camera,
                               int steps) {
  const sim::ClothState<float> coarse = Advance(snapshot, 1, steps), fine = Advance(snapshot, 2, steps);
  const Gap gap = ScreenGap(camera, coarse, fine);
  const double order_factor = std::ldexp(1.0, OrderOf(snapshot.params.integrator));  // 2^p
  FrameDefect defect;
  defect.gap_px = gap.percentile;
  defect.largest_px = gap.largest;
  defect.error_px = order_factor / (order_factor - 1) * gap.percentile;
  defect.substeps = snapshot.substeps * snapshot.guard_factor;
  defect.steps = steps;
  return defect;
}

}  // namespace flagsim::model
