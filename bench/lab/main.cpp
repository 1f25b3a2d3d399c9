// The physics lab: measurements of flagsim's integrators, each an experiment with a table on
// stdout and an optional CSV.
//
//   build/bench/lab EXPERIMENT [--csv FILE]
//   EXPERIMENT: orders | work-precision | stability | cost | threads | cheapest
#include <CLI/CLI.hpp>
#include <functional>
#include <map>

#include "bench/lab/experiments.hpp"

int main(int argc, char** argv) {
  const std::map<std::string, std::function<void(const std::string&)>> experiments = {
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
  CLI11_PARSE(app, argc, argv);
  experiments.at(experiment)(csv);
  return 0;
}
