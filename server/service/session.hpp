// The running session: the scene as it stands now (parameters, wind), the scene it started
// from, and the simulation. Commands arrive here already decoded; each is validated whole
// before it touches anything, so a rejected command leaves the session exactly as it was.
// No LCM here: the service's transport side is command_intake.hpp.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "scene.hpp"
#include "sim/simulation.hpp"

namespace flagsim {

using FlagSimulation = sim::Simulation<float>;

/// `name=value` assignments of one PARAM command, and whether to reset to the scene first.
struct ParamChange {
  bool reset_to_scene = false;
  std::vector<std::pair<std::string, std::string>> assignments;
};

class Session {
 public:
  explicit Session(const Scene& scene);

  /// Applies a wind setting; returns "" or why it was rejected (then nothing changed).
  std::string ApplyWind(const sim::WindSettings& wind);
  /// Applies parameter assignments as one change; returns "" or every reason it was rejected.
  std::string ApplyParams(const ParamChange& change);

  void Step() { simulation_.Step(); }

  const Scene& scene() const { return scene_; }
  const Scene& initial_scene() const { return initial_; }
  const FlagSimulation& simulation() const { return simulation_; }

  static constexpr size_t kMaxAssignments = 64;

 private:
  Scene initial_;
  Scene scene_;
  FlagSimulation simulation_;
};

}  // namespace flagsim
