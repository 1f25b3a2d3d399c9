// A scene: everything a session starts from. Defaults are the "breeze" preset; scene files
// (scene_file.hpp) and PARAM commands override fields through the parameter table.
#pragma once

#include <cstdint>
#include <string>

#include "server/render/camera.hpp"
#include "server/render/pattern.hpp"
#include "server/render/sample_pattern.hpp"
#include "server/render/shading_mode.hpp"
#include "server/scene/design_file.hpp"
#include "server/sim/sim_params.hpp"
#include "server/sim/timeline.hpp"
#include "server/sim/wind_field.hpp"

namespace flagsim {

struct ServiceSettings {
  double state_rate = 60.0;  ///< Hz, STATE messages per second of simulated time
  double frame_rate = 30.0;  ///< Hz, frames per second of simulated time; 0: no frames
  /// Simulated seconds per wall-clock second the live server runs at (frames then follow the
  /// wall clock at frame_rate). Not physics: a reset leaves it alone, and a render ignores it.
  double time_scale = 1.0;
  render::ShadingMode shading = render::ShadingMode::kGouraud;
  render::FlagDesign design = render::FlagDesign::kNordicCross;  ///< what the flag shows
  DesignFilePtr design_file;  ///< the image shown when design is kImage; else none
  /// Whether the flag's width follows the design's aspect (a person's image); false once the
  /// scene file or a PARAM command sets the width.
  bool width_follows_design = true;
  render::Antialiasing antialias = render::Antialiasing::kMsaa4;  ///< samples per pixel of a frame
};

/// What the user left to the server's automatic model (server/model/auto_model.hpp): the
/// integrator (with its iterations), the grid, or both, and the budgets it chooses within. The
/// SimParams hold the model in force, whoever chose it.
struct ModelSettings {
  bool auto_integrator = true;  ///< integrator=auto
  bool auto_grid = true;        ///< cols=auto (rows=auto): the grid at the flag's cols : rows
  double error_budget = 1.0;    ///< px of screen_error allowed
  double cost_budget = 0.8;     ///< CPU seconds per simulated second the flag may take, by the cost model
};

struct Scene {
  static constexpr double kMaxSettle = 60;  ///< s

  std::string name = "breeze";
  std::string description = "A steady breeze with light gusts.";
  uint64_t seed = 1;  ///< gust noise seed
  /// s of simulated time the flag first settles in the scene's physics and wind, before the
  /// session's first step and not streamed, so the session starts from the drape it falls into
  /// (the clock back at 0); 0: it starts flat at rest. 0 .. kMaxSettle.
  double settle = 0;
  sim::SimParams sim;
  sim::WindSettings wind;
  ServiceSettings service;
  ModelSettings model;
  render::Camera camera;   ///< where frames are seen from, and their size
  sim::Timeline timeline;  ///< keyframes driving wind, parameters and camera; empty by default
};

}  // namespace flagsim
