// The running session: the scene as it stands now (parameters, wind, camera, timeline), the
// scene it started from, and the simulation. Pictures of it are drawn elsewhere, from a copy
// (frame_painter.hpp). Commands arrive here
// already decoded; each is validated whole before it touches anything, so a rejected command
// leaves the session exactly as it was. No LCM here: the transport side is command_intake.hpp.
//
// A playing timeline drives the controls its keys set. At each step boundary:
//   evaluate   the timeline at its position (sim/timeline.hpp): wind, parameters, camera
//   apply      into the scene, within limits (scene_timeline.hpp), and into the simulation by
//              its light path: spring constants in place, the wind from now, no checkpoint
//   substeps   on entering a segment between keys (or after an edit), fixed for the least and
//              most of each control the segment reaches, so they stay stable and constant along it
//   step       the simulation, then the position moves on by speed * dt
// Everything is a function of the commands and the step at which each came: a session replays
// bit for bit, at any thread count.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "server/render/camera_moves.hpp"
#include "server/render/camera_on_flag.hpp"
#include "server/scene/scene.hpp"
#include "server/service/geomorph.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim {

using FlagSimulation = sim::Simulation<float>;

/// `name=value` assignments of one PARAM command, and whether to reset to the scene first.
struct ParamChange {
  bool reset_to_scene = false;
  std::vector<std::pair<std::string, std::string>> assignments;
};

/// One KEYFRAME command: an operation on the timeline.
struct TimelineEdit {
  enum Operation { kAdd, kChange, kRemove, kClear, kPlay, kPause, kSeek, kLoop, kSpeed };
  Operation operation = kAdd;
  double time = 0;        ///< s of timeline time: the key to change or remove; the seek target
  double speed = 1;       ///< kSpeed: timeline s per simulated s
  bool loop = false;      ///< kLoop: wrap at the last key
  bool keep_law = false;  ///< kChange: the key keeps its law (key.law is not used)
  /// kAdd: the key, replacing one at its time. kChange: the controls it sets replace the key's
  /// (the others stay), and the key moves to key.time.
  sim::Keyframe key;
};

/// One TIME command: the simulation's clock held, stepped by hand or run on.
struct TimeControl {
  enum Operation { kPause, kResume, kStep };
  Operation operation = kPause;
  int64_t steps = 0;  ///< kStep: steps to take, then paused
};

/// A decision of auto (MODEL, model_governor.hpp): the model to switch to.
struct ModelSwitch {
  sim::IntegratorKind integrator = sim::IntegratorKind::kSymplecticEuler;
  int solver_iterations = 10;
  int cols = 32, rows = 24;
};

/// A session at a step boundary (Session::Snapshot): all its next steps depend on.
struct SessionSnapshot {
  Scene initial;  ///< the scene it started from
  Scene scene;    ///< the scene as it stands
  sim::SimulationSnapshot<float> simulation;
  int timeline_segment = -1;    ///< the segment the substeps were fixed for; -1: none
  bool substeps_fixed = false;  ///< by the timeline
};

class Session {
 public:
  explicit Session(const Scene& scene);
  /// Resumes from a snapshot: its next steps are those the snapshot's session takes.
  explicit Session(const SessionSnapshot& snapshot);

  /// This step boundary as a snapshot (sim::Simulation::Snapshot): a pure read.
  SessionSnapshot Snapshot() const;

  /// Applies a wind setting; returns "" or why it was rejected (then nothing changed).
  std::string ApplyWind(const sim::WindSettings& wind);
  /// Applies parameter assignments as one change; returns "" or every reason it was rejected.
  /// An assignment of the width pins it: a design's image no longer sets it.
  std::string ApplyParams(const ParamChange& change);
  /// Shows a person's image on the flag (design=image), with the width at its aspect unless
  /// pinned; "" or why not (then nothing changed).
  std::string ApplyDesign(const DesignFilePtr& file);

  /// Switches to auto's decision where auto is on: the integrator and its iterations under
  /// integrator=auto, the grid under cols=auto. "" or why not (then nothing changed). A grid
  /// change keeps the motion (Simulation::Regrid); after a coarsening, frames fade out the finer
  /// grid's wrinkles (geomorph.hpp).
  std::string ApplyModel(const ModelSwitch& model);

  /// The blend from a finer grid while it lasts (Geomorph::Blends), else null. Frames only: a
  /// checkpoint does not carry it.
  const Geomorph* geomorph() const;

  /// Applies a camera move (kReset: back to the scene's camera); "" or why it was rejected.
  std::string ApplyCamera(const render::CameraMove& move);

  /// Edits or drives the timeline; "" or why it was rejected (then nothing changed). Where the
  /// change would make the controls jump during play (play, seek, a key added, changed or
  /// removed) they glide from the values in force instead.
  std::string ApplyTimeline(const TimelineEdit& edit);

  /// Pauses, resumes or steps the simulation's clock; "" or why it was rejected (then nothing
  /// changed). Only the live server's loop reads it (Runs, StepsOwed); a replay steps as the
  /// journal says, so a session with pauses replays as one without them.
  std::string ApplyTime(const TimeControl& control);
  /// Whether the live clock runs: not paused, or steps a kStep asked for are still owed.
  bool Runs() const { return !paused_ || steps_owed_ > 0; }
  bool paused() const { return paused_; }
  int64_t steps_owed() const { return steps_owed_; }

  static constexpr int64_t kMaxStepsOwed = 100000;  ///< steps a kStep may ask for, with those still owed

  /// One step of the flag, under the timeline's controls if it plays. If the guard replaced the
  /// integrator, the scene follows (PARAMS shows it, and the next PARAM builds on it); returns
  /// true then.
  bool Step();

  /// Counts accepted changes to what a frame shows (wind, parameters, camera, the camera moved
  /// by the timeline).
  int64_t revision() const { return revision_; }

  const Scene& scene() const { return scene_; }
  const Scene& initial_scene() const { return initial_; }
  const FlagSimulation& simulation() const { return simulation_; }

  static constexpr size_t kMaxAssignments = 64;

 private:
  /// The flag's nodes now, for the camera moves that aim at it (render/camera_on_flag.hpp).
  render::FlagSurface FlagSurfaceNow() const;
  static constexpr int kNoSegment = -1;
  /// ApplyParams, with `image` as the design's image (null: the one in force).
  std::string Change(const ParamChange& change, const DesignFilePtr& image);
  void FollowTimeline();
  void ApplyTimelineControls();
  void FixSubsteps(double position);
  sim::WindControl WindNow() const;

  Scene initial_;
  Scene scene_;
  FlagSimulation simulation_;
  int64_t revision_ = 0;
  std::optional<Geomorph> geomorph_;
  int substeps_segment_ = kNoSegment;  ///< the timeline segment the substeps were fixed for
  bool paused_ = false;                ///< TIME pause, or a TIME step's steps taken
  int64_t steps_owed_ = 0;             ///< steps a TIME step has still to take
  bool substeps_fixed_ = false;        ///< by the timeline, not by the simulation's own choice
};

}  // namespace flagsim
