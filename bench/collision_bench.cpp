// What self-collision costs and what it buys: the breeze preset at 32 x 24 to 256 x 192 nodes
// (and calm and gale at 32 x 24), one simulation with self_collision off and one with it on,
// stepped in the same run on one thread.
//
//   build/bench/collision_bench [--csv FILE] [--repetitions N] [--seconds S] [--max-cols C]
//                               [--set NAME=VALUE ...]
//
// --set overrides a parameter of every preset before its grid is scaled (integrator=xpbd,
// solver_iterations=2: the model auto takes at fine grids).
//
// The run: both simulations from rest over S / scale seconds of simulated time (scale = cols / 32,
// so 10, 5, 2.5 and 1.25 s by default: the big grids are slow), taking turns one STATE interval
// (60 Hz) at a time. At every STATE, crossing pairs of triangles are counted in each by the
// independent checker (lab/triangle_crossings.hpp), untimed:
//   crossings per second = (sum over the sampled states) / (seconds simulated)
// and the stepping's thread CPU time is summed: run_ms = CPU time / steps, the cost of exactly
// the motion whose crossings were counted.
//
// The timing: each simulation's state at the end of the run (a snapshot) is stepped K steps
// (K fills about kTimedSeconds of CPU time with self-collision off), N times, off and on taking
// turns and the one to go first alternating, every repetition from the same snapshot:
//   ms_off, ms_on = medians over repetitions of CPU ms per step
//   ratio         = median over repetitions of on / off in the same repetition
// The machine is shared: ratios measured in one run are what to compare, not times across runs.
//
// Columns of the table and the CSV: preset, cols, rows, substeps (per step), seconds (simulated),
// ms_off, ms_on, ratio, run_ms_off, run_ms_on, run_ratio, patch_pairs, candidates, contacts, held
// (means per step with self-collision on, summed over its passes: pairs of patches examined,
// primitive pairs whose swept boxes overlap, impulses, nodes the fail-safe kept still),
// crossings_per_s_off, crossings_per_s_on, passes (of self-collision per step, mean).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bench/lab/table.hpp"
#include "lab/cpu_time.hpp"
#include "lab/triangle_crossings.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/scene/scene_file.hpp"
#include "server/sim/cloth_mesh.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim::bench {
namespace {

using lab::Table;
using Simulation = sim::Simulation<float>;

constexpr double kTimedSeconds = 0.2;  ///< s of CPU time per timed repetition, self-collision off
constexpr int kLeastTimedSteps = 3;

struct Options {
  std::string csv;      ///< "" writes no CSV
  int repetitions = 5;  ///< timed repetitions per grid
  double seconds = 10;  ///< s of simulated time at 32 x 24; S / scale at larger grids
  int max_cols = 256;   ///< grids wider than this are left out
  std::vector<std::string> assignments;  ///< NAME=VALUE, applied to every preset
};

/// A preset at 32 * scale x 24 * scale nodes.
struct Case {
  std::string preset;
  int scale = 1;
};

/// One setting (self-collision off or on) over the run: the simulation and what it cost and did.
struct Run {
  std::unique_ptr<Simulation> simulation;
  double cpu_seconds = 0;  ///< of stepping alone
  int64_t steps = 0;
  int64_t crossings = 0;  ///< crossing triangle pairs, summed over the sampled states
  double passes = 0, patch_pairs = 0, candidates = 0, contacts = 0,
         held = 0;  ///< sums over steps of self_collision_stats()
};

Run StartRun(const Scene& scene, const sim::SimParams& params, bool self_collision) {
  sim::SimParams setting = params;
  setting.self_collision = self_collision;
  return Run{std::make_unique<Simulation>(setting, scene.wind, scene.seed)};
}

/// `steps` steps of run's simulation, each timed in thread CPU seconds; its statistics summed.
void StepTimed(int steps, Run* run) {
  for (int i = 0; i < steps; ++i) {
    const double start = lab::ThreadCpuSeconds();
    run->simulation->Step();
    run->cpu_seconds += lab::ThreadCpuSeconds() - start;
    const sim::SelfCollisionStats& stats = run->simulation->self_collision_stats();
    run->passes += stats.passes;
    run->patch_pairs += stats.patch_pairs;
    run->candidates += stats.candidates;
    run->contacts += stats.contacts;
    run->held += stats.held;
    ++run->steps;
  }
}

void CountCrossings(const sim::ClothMesh& mesh, Run* run) {
  const sim::ClothState<float>& state = run->simulation->state();
  run->crossings += lab::CrossingTrianglePairs(mesh.triangles, state.x, state.y, state.z);
}

/// Both settings from rest over `seconds`, in turns of one STATE interval, crossings counted at
/// every STATE.
void RunBoth(double seconds, int steps_per_state, const sim::ClothMesh& mesh, Run* off, Run* on) {
  while (on->simulation->state().time < seconds) {
    StepTimed(steps_per_state, off);
    StepTimed(steps_per_state, on);
    CountCrossings(mesh, off);
    CountCrossings(mesh, on);
  }
}

/// Thread CPU seconds per step of `steps` steps from `snapshot` (the simulation built untimed).
double SecondsPerStep(const sim::SimulationSnapshot<float>& snapshot, int steps) {
  Simulation simulation(snapshot);
  const double start = lab::ThreadCpuSeconds();
  for (int i = 0; i < steps; ++i) simulation.Step();
  return (lab::ThreadCpuSeconds() - start) / steps;
}

double Median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

struct Timing {
  double off = 0, on = 0;  ///< s per step, medians over repetitions
  double ratio = 0;        ///< median over repetitions of on / off
};

/// Off and on from their snapshots, `repetitions` times in turns, the first to go alternating.
Timing TimeInTurns(const sim::SimulationSnapshot<float>& off, const sim::SimulationSnapshot<float>& on,
                   int steps, int repetitions) {
  std::vector<double> off_seconds, on_seconds, ratios;
  for (int r = 0; r < repetitions; ++r) {
    double off_time = 0, on_time = 0;
    if (r % 2 == 0) {
      off_time = SecondsPerStep(off, steps);
      on_time = SecondsPerStep(on, steps);
    } else {
      on_time = SecondsPerStep(on, steps);
      off_time = SecondsPerStep(off, steps);
    }
    off_seconds.push_back(off_time);
    on_seconds.push_back(on_time);
    ratios.push_back(on_time / off_time);
  }
  return {Median(off_seconds), Median(on_seconds), Median(ratios)};
}

/// One case: the run, then the timing from where the run ended; a row of the table.
void Measure(const Case& one, const Options& options, Table* table) {
  Scene scene = LoadScene(one.preset);
  for (const std::string& assignment : options.assignments) {
    const std::size_t equals = assignment.find('=');
    const std::string problem =
        equals == std::string::npos ? "expected NAME=VALUE"
                                    : ParameterTable::Get().Assign(assignment.substr(0, equals),
                                                                   assignment.substr(equals + 1), &scene);
    if (!problem.empty()) throw SceneError("--set " + assignment + ": " + problem);
  }
  sim::SimParams params = scene.sim;
  params.cols *= one.scale;
  params.rows *= one.scale;
  const double seconds = options.seconds / one.scale;
  const int steps_per_state = int(std::lround(1 / (scene.service.state_rate * params.dt)));
  Run off = StartRun(scene, params, false), on = StartRun(scene, params, true);
  RunBoth(seconds, steps_per_state, sim::BuildClothMesh(params.cols, params.rows), &off, &on);
  const double run_off = off.cpu_seconds / off.steps, run_on = on.cpu_seconds / on.steps;
  const int timed_steps = std::max(kLeastTimedSteps, int(std::ceil(kTimedSeconds / run_off)));
  const Timing timing =
      TimeInTurns(off.simulation->Snapshot(), on.simulation->Snapshot(), timed_steps, options.repetitions);
  const double simulated = on.simulation->state().time, steps = double(on.steps);
  table->Add({one.preset, std::to_string(params.cols), std::to_string(params.rows),
              std::to_string(on.simulation->substeps()), Table::Number(simulated),
              Table::Number(1e3 * timing.off), Table::Number(1e3 * timing.on), Table::Number(timing.ratio),
              Table::Number(1e3 * run_off), Table::Number(1e3 * run_on), Table::Number(run_on / run_off),
              Table::Number(on.patch_pairs / steps), Table::Number(on.candidates / steps),
              Table::Number(on.contacts / steps), Table::Number(on.held / steps),
              Table::Number(double(off.crossings) / simulated),
              Table::Number(double(on.crossings) / simulated), Table::Number(on.passes / steps)});
}

}  // namespace
}  // namespace flagsim::bench

int main(int argc, char** argv) {
  flagsim::bench::Options options;
  CLI::App app{
      "collision_bench: the cost of self-collision per step, and crossing pairs without and with it"};
  app.add_option("--csv", options.csv, "also write the table to this CSV file");
  app.add_option("--repetitions", options.repetitions, "timed repetitions per grid")
      ->check(CLI::PositiveNumber);
  app.add_option("--seconds", options.seconds, "simulated seconds at 32 x 24 (divided by the scale above)")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-cols", options.max_cols, "leave out grids wider than this (32 for 32 x 24 alone)")
      ->check(CLI::PositiveNumber);
  app.add_option("--set", options.assignments, "override a parameter of every preset: NAME=VALUE (repeatable)");
  CLI11_PARSE(app, argc, argv);
  flagsim::lab::Table table({"preset", "cols", "rows", "substeps", "seconds", "ms_off", "ms_on", "ratio",
                             "run_ms_off", "run_ms_on", "run_ratio", "patch_pairs", "candidates", "contacts",
                             "held", "crossings_per_s_off", "crossings_per_s_on", "passes"},
                            options.csv);
  const std::vector<flagsim::bench::Case> cases = {{"breeze", 1}, {"breeze", 2}, {"breeze", 4},
                                                   {"breeze", 8}, {"calm", 1},   {"gale", 1}};
  try {
    for (const flagsim::bench::Case& one : cases) {
      if (32 * one.scale <= options.max_cols) flagsim::bench::Measure(one, options, &table);
    }
  } catch (const flagsim::SceneError& error) {
    std::fprintf(stderr, "collision_bench: %s\n", error.what());
    return 2;
  }
  return 0;
}
