// The running session: the scene as it stands now (parameters, wind, camera), the scene it
// started from, the simulation, and the renderer that draws it. Commands arrive here already
// decoded; each is validated whole before it touches anything, so a rejected command leaves
// the session exactly as it was. No LCM here: the transport side is command_intake.hpp.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "render/camera_moves.hpp"
#include "render/renderer.hpp"
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

  /// Applies a camera move (kReset: back to the scene's camera); "" or why it was rejected.
  std::string ApplyCamera(const render::CameraMove& move);

  /// One step of the flag. If the guard replaced the integrator, the scene follows (PARAMS shows
  /// it, and the next PARAM builds on it); returns true then.
  bool Step();

  /// Draws the flag as it is now with the session's camera and shading, on `threads` threads.
  const render::Framebuffer& RenderFrame(int threads);
  const render::Framebuffer& frame() const { return framebuffer_; }

  /// Counts accepted changes to what a frame shows (wind, parameters, camera).
  int64_t revision() const { return revision_; }

  const Scene& scene() const { return scene_; }
  const Scene& initial_scene() const { return initial_; }
  const FlagSimulation& simulation() const { return simulation_; }

  static constexpr size_t kMaxAssignments = 64;

 private:
  Scene initial_;
  Scene scene_;
  FlagSimulation simulation_;
  render::RenderScene render_scene_;
  render::Renderer renderer_;
  render::Framebuffer framebuffer_;
  int64_t revision_ = 0;
};

}  // namespace flagsim
