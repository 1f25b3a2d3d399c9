// screen_error as the server bounds it: the defect of a frame interval, in pixels.
//
// A fluttering flag is chaotic, so the distance of a run from a reference saturates within a
// fraction of a second and means nothing past it. What the viewer sees accumulate is the error
// made frame by frame: from one state, the gap between one frame interval advanced at the model's
// substep h and the same interval at h / 2, projected through the camera in force, a high
// percentile over the nodes. Richardson's extrapolation turns the gap into the error of the run
// at h: for a method of order p, e(h) = 2^p / (2^p - 1) |x(h) - x(h/2)| to leading order (twice
// the gap for first-order methods, 16/15 of it for RK4).
//
// Deterministic (both runs start from the same snapshot and step as the server would, guard and
// collisions included, at any thread count) and online: it costs three frame intervals of
// simulation, which the server spends every so often, not every frame.
#pragma once

#include "server/render/camera.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim::model {

/// The percentile of the nodes' gaps that screen_error reports.
inline constexpr double kDefectPercentile = 0.95;

struct FrameDefect {
  double gap_px = 0;       ///< the kDefectPercentile gap between the runs at h and h / 2
  double largest_px = 0;   ///< the largest gap
  double error_px = 0;     ///< gap_px extrapolated to the error of the run at h (Richardson)
  int substeps = 0;        ///< per step at h, the guard's factor included
  int steps = 0;           ///< steps in the frame interval
};

/// The defect of the frame interval from `snapshot`: `steps` steps at the snapshot's substeps
/// and at twice them, the nodes projected through `camera`.
FrameDefect MeasureFrameDefect(const sim::SimulationSnapshot<float>& snapshot, const render::Camera& camera,
                               int steps);

/// The integrator's order of accuracy p: 1, 2 or 4.
int OrderOf(sim::IntegratorKind kind);

/// Projected gaps between the nodes of two states, px: the kDefectPercentile one and the largest.
/// A node behind the eye in either counts as infinitely far.
struct Gap {
  double percentile = 0, largest = 0;
};
Gap ScreenGap(const render::Camera& camera, const sim::ClothState<float>& a, const sim::ClothState<float>& b);

}  // namespace flagsim::model
