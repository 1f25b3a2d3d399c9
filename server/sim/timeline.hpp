// The keyframe timeline (the seed's method): keys fix the flag's controls at chosen moments, a
// control law moves each control from one key to the next, and every step in between is
// simulated under the interpolated controls.
//
// Controls: the wind (mean velocity and gust), numeric parameters by name (the parameter table
// decides which names a key may set, server/scene/scene_timeline.hpp), and the camera (eye,
// target, vertical field of view). Each control has its own track: the keys that set it. A key
// that does not set a control does not interrupt it; between two keys of its track a control
// follows the law of the earlier one (control_laws.hpp), the cubic reading the track's keys
// around them; before its first key and after its last it holds their values.
//   scalars         the law on the values (parameters, gust, the camera's coordinates and fov)
//   wind velocity   speed by the law; direction along the great circle between the keys' (Slerp)
//                   by the law's fraction of the turn, so that a swinging wind keeps its strength
//
// Time: the timeline's position (s) moves by speed * dt per simulated step of dt, never by wall
// time; past its last key it stops, or with loop wraps to 0. A glide smooths the controls that
// a command would otherwise make jump (play, seek, an edit during play): the jump, the values in
// force less the timeline's own at that moment, dies away by the smooth law over kGlideTime of
// simulated time. An edit that leaves the values at the position as they were changes nothing.
//
// A plain value: keys, play state and glide are all it holds (no clock, no cache), so a copy is
// a checkpoint. It checks nothing; server/scene/scene_timeline.hpp validates keys and limits.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "server/sim/control_laws.hpp"
#include "server/sim/wind_field.hpp"

namespace flagsim::sim {

/// The wind a key sets, as a WIND command gives it.
struct WindControl {
  Vec3 velocity{};  ///< m/s, world frame
  double gust = 0;  ///< gust strength, fraction of |velocity|
};

/// The camera a key sets: eye and target as the scene's camera holds them.
struct CameraControl {
  Vec3 eye{};       ///< m
  Vec3 target{};    ///< m, the point looked at
  double fov = 40;  ///< degrees, vertical field of view
};

/// A numeric parameter a key sets: a name of the parameter table and its value in its unit.
struct ParameterControl {
  std::string name;
  double value = 0;
};

/// The controls at one moment; unset ones are left as they are.
struct Controls {
  std::optional<WindControl> wind;
  std::vector<ParameterControl> parameters;  ///< sorted by name, each name once
  std::optional<CameraControl> camera;
};

struct Keyframe {
  double time = 0;                       ///< s of timeline time
  ControlLaw law = ControlLaw::kLinear;  ///< from this key to the next key of each control's track
  std::optional<WindControl> wind;
  std::vector<ParameterControl> parameters;  ///< each name once
  std::optional<CameraControl> camera;

  /// The value this key sets for parameter `name`, or nullptr.
  const double* Parameter(const std::string& name) const;
};

/// The range of one parameter over a stretch of the timeline (see ParameterRanges).
struct ParameterRange {
  std::string name;
  double low = 0, high = 0;  ///< in the parameter's unit
};

class Timeline {
 public:
  static constexpr double kGlideTime = 0.25;  ///< s of simulated time a glide takes

  // ---- keys -----------------------------------------------------------------------------------
  /// Keys in time order, at distinct times.
  const std::vector<Keyframe>& keys() const { return keys_; }
  /// Inserts `key`, replacing a key at the same time. Returns true if it replaced one.
  bool Add(const Keyframe& key);
  /// Removes the key at `time`; false if there is none. A position past the new last key moves to
  /// it; with no key left the position goes back to 0, as after Clear.
  bool Remove(double time);
  /// Removes every key; the position goes back to 0 (play, loop and speed stay).
  void Clear();
  /// The key at exactly `time`, or nullptr.
  const Keyframe* Find(double time) const;
  /// s: the last key's time (0 without keys); where the timeline stops, or wraps with loop.
  double End() const { return keys_.empty() ? 0.0 : keys_.back().time; }

  // ---- playing --------------------------------------------------------------------------------
  bool playing() const { return playing_; }
  double position() const { return position_; }  ///< s of timeline time
  double speed() const { return speed_; }        ///< timeline s per simulated s
  bool loop() const { return loop_; }
  void Play() { playing_ = true; }
  void Pause() { playing_ = false; }
  /// Moves to `position` (s); a glide in progress ends.
  void Seek(double position);
  void SetSpeed(double speed) { speed_ = speed; }
  void SetLoop(bool loop) { loop_ = loop; }

  /// One simulated step of dt s: the position moves by speed dt, a glide under way by dt. Past
  /// End the position wraps (loop) or stays at End, and playing stops once a step that starts
  /// at End has been taken with no glide under way; without keys nothing moves.
  void Advance(double dt);

  // ---- evaluation -----------------------------------------------------------------------------
  /// The controls at `position` (s of timeline time), blended with the glide under way if any.
  Controls Evaluate(double position) const;
  /// Which stretch between keys `position` is in: the number of keys at or before it.
  int SegmentAt(double position) const;
  /// For each parameter some key sets: the least and most it takes over the segment that holds
  /// `position` (cubic overshoot included), widened by the jump a glide under way has left.
  std::vector<ParameterRange> ParameterRanges(double position) const;

  /// From now on, the controls glide from `from` (the values in force) to the timeline's over
  /// kGlideTime: with j = from - (the timeline's values now), Evaluate gives timeline + j (1 - w),
  /// w the smooth law's fraction of the glide's time gone by. For the wind j is a change of speed
  /// and a turn, which die away alike. Controls `from` does not hold follow the timeline at once.
  void StartGlide(const Controls& from);
  bool gliding() const { return glide_.has_value(); }

  /// A glide under way: how long it has run, and the jump it smooths: from the timeline's values
  /// when it started (`start`) to the values then in force (`from`).
  struct Glide {
    double elapsed = 0;  ///< s of simulated time since it started
    Controls from;
    Controls start;
  };
  /// The glide under way, and setting one back (from a checkpoint).
  const std::optional<Glide>& glide() const { return glide_; }
  void RestoreGlide(const std::optional<Glide>& glide) { glide_ = glide; }

  bool operator==(const Timeline& other) const;
  bool operator!=(const Timeline& other) const { return !(*this == other); }

 private:
  Controls Interpolated(double position) const;

  std::vector<Keyframe> keys_;
  bool playing_ = false;
  double position_ = 0;  ///< s of timeline time
  double speed_ = 1;     ///< timeline s per simulated s
  bool loop_ = false;
  std::optional<Glide> glide_;
};

bool operator==(const WindControl& a, const WindControl& b);
bool operator==(const CameraControl& a, const CameraControl& b);
bool operator==(const ParameterControl& a, const ParameterControl& b);
bool operator==(const Controls& a, const Controls& b);
bool operator==(const Keyframe& a, const Keyframe& b);

}  // namespace flagsim::sim
