// The physics lab: measurements of flagsim's integrators, each an experiment with a table on
// stdout and an optional CSV.
//
//   build/bench/lab EXPERIMENT [--csv FILE]
//   EXPERIMENT: orders | work-precision | stability | cost | threads | cheapest | shape | horizon | views |
//   cost-model | auto shape also takes --scene, --grid (repeated), --set NAME=VALUE (repeated), --warmup,
//   --seconds, --batches
//   build/bench/lab points|point|gather ...: an experiment as independent points, for
//   scripts/sweep (sweep_points.hpp)
#include <CLI/CLI.hpp>
#include <functional>
#include <map>

#include "bench/lab/experiments.hpp"
#include "bench/lab/sweep_points.hpp"

namespace {

/// lab points | point | gather: an experiment as independent points (sweep_points.hpp), for
/// scripts/sweep. Returns the exit code, or -1 if argv names none of them.
int SweepCommand(int argc, char** argv) {
  const std::string command = argc > 1 ? argv[1] : "";
  if (command != "points" && command != "point" && command != "gather") return -1;
  CLI::App app{"lab " + command + ": an experiment as independent points (scripts/sweep runs them)"};
  std::string experiment, directory, points;
  flagsim::lab::PointsOptions options;
  int index = 0, chunk = 1;
  if (command == "points") {
    app.add_option("experiment", experiment, "work-precision or render")->required();
    app.add_option("--out", directory, "the sweep's folder: points.txt goes there")->required();
    app.add_flag("--quick", options.quick, "work-precision: two integrators at three steps (a test's sweep)");
    app.add_option("--scene", options.scenes, "render: a preset or scene file (repeat for several)");
    app.add_option("--duration", options.duration, "render: s of simulated time")->check(CLI::PositiveNumber);
    app.add_option("--fps", options.fps, "render: frames per simulated second")->check(CLI::PositiveNumber);
  } else {
    app.add_option("--points", points, "the sweep's points.txt")->required()->check(CLI::ExistingFile);
    app.add_option("--chunk", chunk, "points per task")->check(CLI::PositiveNumber);
    if (command == "point")
      app.add_option("--index", index, "the task: 0, 1, ...")->required()->check(CLI::NonNegativeNumber);
  }
  try {
    app.parse(argc - 1, argv + 1);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }
  try {
    if (command == "points") {
      std::printf("%d points\n", flagsim::lab::WritePoints(experiment, options, directory));
      return 0;
    }
    if (command == "point") return flagsim::lab::RunPoints(points, index, chunk);
    return flagsim::lab::GatherRecords(points, chunk);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "lab %s: %s\n", command.c_str(), error.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (const int code = SweepCommand(argc, argv); code >= 0) return code;
  flagsim::lab::ShapeOptions shape;
  const std::map<std::string, std::function<void(const std::string&)>> experiments = {
      {"shape", [&](const std::string& csv) { flagsim::lab::Shape(shape, csv); }},
      {"horizon", flagsim::lab::AgreementHorizon},
      {"views", flagsim::lab::Views},
      {"cost-model", flagsim::lab::CostModelFit},
      {"auto", flagsim::lab::AutoChoice},
      {"orders", flagsim::lab::Orders},
      {"work-precision", flagsim::lab::WorkPrecision},
      {"stability", flagsim::lab::StabilityMap},
      {"cost", flagsim::lab::Cost},
      {"threads", flagsim::lab::Threads},
      {"cheapest", flagsim::lab::Cheapest},
  };
  CLI::App app{"lab: how flagsim's integrators compare in accuracy, stability, cost and threads"};
  std::string experiment, csv;
  std::vector<std::string> names;
  for (const auto& [name, run] : experiments) names.push_back(name);
  app.add_option("experiment", experiment, "which measurement")->required()->check(CLI::IsMember(names));
  app.add_option("--csv", csv, "also write the table to this CSV file");
  app.add_option("--scene", shape.scene, "shape: the preset or scene file");
  app.add_option("--grid", shape.grids, "shape: a grid COLSxROWS (repeat for several)");
  app.add_option("--set", shape.settings, "shape: NAME=VALUE, a parameter for every grid (repeatable)");
  app.add_option("--warmup", shape.warmup, "shape: seconds before sampling");
  app.add_option("--seconds", shape.seconds, "shape: seconds sampled");
  app.add_option("--batches", shape.batches, "shape: batches for the confidence intervals");
  CLI11_PARSE(app, argc, argv);
  experiments.at(experiment)(csv);
  return 0;
}
