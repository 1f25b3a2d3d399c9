// The cloth under grid refinement: a preset scene at several grids, each run through the server's
// own simulation (float, automatic substeps, self-collision) past a warm-up, sampled at 50 Hz,
// reduced to shape statistics with 95% confidence intervals (lab/shape_statistics.hpp).
// A cloth whose model converges keeps them at every grid; one whose folds are set by the grid
// spacing shows its curvature growing and its fold spacing shrinking as the grid refines.
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "bench/lab/experiments.hpp"
#include "bench/lab/table.hpp"
#include "lab/cpu_time.hpp"
#include "lab/shape_statistics.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/scene/scene_file.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim::lab {
namespace {

constexpr double kSampleInterval = 0.02;  ///< s

Scene SceneAt(const ShapeOptions& options, const std::string& grid) {
  Scene scene = LoadScene(options.scene);
  int cols = 0, rows = 0;
  if (std::sscanf(grid.c_str(), "%dx%d", &cols, &rows) != 2) {
    throw std::invalid_argument("grid '" + grid + "': expected COLSxROWS, as 64x48");
  }
  std::vector<std::pair<std::string, std::string>> settings = {{"cols", std::to_string(cols)},
                                                               {"rows", std::to_string(rows)}};
  for (const std::string& assignment : options.settings) {
    const size_t equals = assignment.find('=');
    if (equals == std::string::npos) throw std::invalid_argument("--set '" + assignment + "': expected NAME=VALUE");
    settings.emplace_back(assignment.substr(0, equals), assignment.substr(equals + 1));
  }
  for (const auto& [name, value] : settings) {
    const std::string problem = ParameterTable::Get().Assign(name, value, &scene);
    if (!problem.empty()) throw std::invalid_argument(problem);
  }
  scene.sim.threads = 1;
  return scene;
}

}  // namespace

void Shape(const ShapeOptions& options, const std::string& csv) {
  std::printf("# %s, warm-up %g s, then %g s sampled every %g s in %d batches; +- is the 95%% interval\n",
              options.scene.c_str(), options.warmup, options.seconds, kSampleInterval, options.batches);
  Table table({"grid", "reach_m", "reach_ci", "height_m", "height_ci", "spread_m", "spread_ci", "curvature_per_m",
               "curvature_ci", "fold_along_m", "fold_along_ci", "fold_down_m", "fold_down_ci", "flutter_hz",
               "flutter_ci", "cpu_s_per_s"},
              csv);
  for (const std::string& grid : options.grids) {
    const Scene scene = SceneAt(options, grid);
    sim::Simulation<float> simulation(scene.sim, scene.wind, scene.seed);
    const int per_sample = std::max(1, int(std::lround(kSampleInterval / scene.sim.dt)));
    const auto steps_for = [&](double seconds) { return int(std::lround(seconds / scene.sim.dt)); };
    const double start = ThreadCpuSeconds();
    for (int i = 0; i < steps_for(options.warmup); ++i) simulation.Step();
    std::vector<ShapeSample> samples;
    for (int i = 0; i < steps_for(options.seconds); ++i) {
      simulation.Step();
      if ((i + 1) % per_sample == 0) samples.push_back(SampleShape(simulation.model(), simulation.state()));
    }
    const double cost = (ThreadCpuSeconds() - start) / (options.warmup + options.seconds);
    const ShapeStatistics s = SummariseShape(samples, options.batches);
    std::vector<std::string> row = {grid};
    for (const Estimate& e : {s.reach, s.height, s.spread, s.curvature, s.fold_along, s.fold_down, s.flutter}) {
      row.push_back(Table::Number(e.mean));
      row.push_back(Table::Number(e.half_width));
    }
    row.push_back(Table::Number(cost));
    table.Add(row);
  }
}

}  // namespace flagsim::lab
