// The physics lab's experiments. Each prints a table and, given a path, writes it as CSV; the
// charts in docs/ are drawn from those files (bench/charts/lab.sh).
#pragma once

#include <string>
#include <vector>

namespace flagsim::lab {

/// Convergence orders: log-log slopes of error against step for each integrator.
void Orders(const std::string& csv);
/// Work against precision: error (m and px) against CPU cost per simulated second, every
/// integrator over a sweep of steps (and iterations for xpbd and projective).
void WorkPrecision(const std::string& csv);
/// Stability map: the largest stable step against structural stiffness, with the theory.
void StabilityMap(const std::string& csv);
/// Cost per node-substep of every integrator from 32 x 24 to 512 x 384 nodes, one thread, and
/// the memory each adds per node.
void Cost(const std::string& csv);
/// Thread sweep: wall time per step at 1 and 2 threads, speedup and efficiency.
void Threads(const std::string& csv);
/// For each preset scene, the cheapest integrator and step whose error stays under a pixel.
void Cheapest(const std::string& csv);

/// How long two grids, and each method and a reference, agree point by point on each preset.
void AgreementHorizon(const std::string& csv);

/// The cost model's constants (server/model/cost_model.hpp), fitted on one thread.
void CostModelFit(const std::string& csv);

/// What auto chooses per preset and view, estimated and measured, beside the preset's own model.
void AutoChoice(const std::string& csv);

/// What each view needs: every preset's screen_error per grid at three distances, two image sizes.
void Views(const std::string& csv);

/// What the shape experiment runs: a scene at several grids, with settings of its own.
struct ShapeOptions {
  std::string scene = "breeze";
  std::vector<std::string> grids = {"32x24", "64x48", "128x96"};
  std::vector<std::string> settings;  ///< NAME=VALUE, as flagd --set takes them
  double warmup = 4;                  ///< s before sampling
  double seconds = 20;                ///< s sampled
  int batches = 10;
};
/// The cloth under grid refinement: shape statistics with confidence intervals at each grid.
void Shape(const ShapeOptions& options, const std::string& csv);

}  // namespace flagsim::lab
