// The physics lab: measurements of flagsim's integrators, each an experiment with a table on
// stdout and an optional CSV.
//
//   build/bench/lab EXPERIMENT [--csv FILE]
//   EXPERIMENT: orders | work-precision | stability | cost | threads | cheapest | shape | horizon | views | cost-model | auto
//   shape also takes --scene, --grid (repeated), --set NAME=VALUE (repeated), --warmup,
//   --seconds, --batches
#include <CLI/CLI.hpp>
#include <functional>
#include <map>

#include "bench/lab/experiments.hpp"

int main(int argc, char** argv) {
  flagsim::lab::ShapeOptions shape;
  const std::map<std::string, std::function<void(const std::string&)>> experiments = {
      {"shape", [&](const std::string& csv) { flagsim::lab::Shape(shape, csv); }},
      {"horizon", flagsim::lab::AgreementHorizon},
      {"views", flagsim::lab::Views},
      {"cost-model", flagsim::lab::CostModelFit},
      {"auto", flagsim::lab::AutoChoice},
      {"orders", flagsim::lab::Orders},          {"work-precision", flagsim::lab::WorkPrecision},
      {"stability", flagsim::lab::StabilityMap}, {"cost", flagsim::lab::Cost},
      {"threads", flagsim::lab::Threads},        {"cheapest", flagsim::lab::Cheapest},
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
