// The keyframe timeline (sim/timeline.hpp) in the scene's terms: what a key may set and the
// limits of a key and of a whole timeline (KEYFRAME commands and scene files are checked alike),
// the evaluated controls written into a scene, and the settings a stretch of the timeline
// passes through (from which the simulation's substeps are chosen).
//
// A key sets only animatable parameters: the forces' continuous coefficients (stiffness,
// shear_stiffness, bending_stiffness, damping, friction, wind_coefficient, gravity), which a step
// changes in place. The others are rejected in keys, not stepped: grid and mass changes rebuild
// the flag at rest, dt and the numerics would change the step under the timeline, and integers,
// choices and switches have nothing between their values; PARAM sets them.
#pragma once

#include <string>
#include <vector>

#include "server/scene/scene.hpp"
#include "server/sim/timeline.hpp"

namespace flagsim {

struct TimelineLimits {
  static constexpr size_t kMaxKeys = 256;
  static constexpr size_t kMaxKeyParameters = 64;       ///< a key sets at most these many (and each once)
  static constexpr double kMaxTime = 86400;             ///< s of timeline time: keys and seeks, 0 .. a day
  static constexpr double kMaxSpeed = 100;              ///< timeline s per simulated s; speeds are > 0
  static constexpr double kMinFov = 10, kMaxFov = 120;  ///< degrees, a key's camera
  static constexpr double kMinCameraGap = 1e-3;         ///< m between a key's eye and target
};

/// The parameters a key may set, in the table's order.
std::vector<std::string> AnimatableNames();

/// "" or "field: value is out of range; allowed 0 .. 86400 s": a key's time or a seek's target.
std::string CheckTimelineTime(const std::string& field, double time);
/// "" or "field: value; allowed above 0, up to 100 ...": a playing speed.
std::string CheckTimelineSpeed(const std::string& field, double speed);
/// "2.5 s": a time in reasons, shortest exact.
std::string SecondsText(double seconds);
/// "0, 2, 4.5 s": the keys' times, for reasons that name a key that is not there.
std::string KeyTimes(const sim::Timeline& timeline);

/// "" or what is wrong with one key, named `what` ("key", "timeline.keys[2]"), its field named:
/// "key.wind.velocity.x: ...", "key.parameters.cols: ...", "key.camera.fov: ...".
std::string CheckKeyframe(const sim::Keyframe& key, const std::string& what);

/// "" or what is wrong with `timeline` as it would drive `scene`: too many keys, a bad key
/// ("keys[3]: ..."), a position or speed out of range, or settings the keys reach that
/// the scene's integrator cannot take (the seed integrator's friction, more substeps per step
/// than sim::kMaxSubsteps at the stiffest controls).
std::string CheckTimeline(const sim::Timeline& timeline, const Scene& scene);

/// Writes evaluated controls into `scene`: parameters within the table's ranges, the wind
/// within the speed and gust limits and at once (no ramp), the camera's fov within limits and
/// its eye and target within kMaxDistance (kept as they were if they would meet). A cubic may
/// overshoot its keys; what reaches the scene is always allowed.
void ApplyControls(const sim::Controls& controls, Scene* scene);

/// For each control the timeline sets, its value in force now: the parameters and camera of
/// `scene`, and `wind_now`, the mean wind the flag feels (a ramp may be under way). A glide
/// starts from these.
sim::Controls ControlsInForce(const Scene& scene, const sim::Timeline& timeline,
                              const sim::WindControl& wind_now);

/// The least and the most of each control the timeline sets over the segment holding
/// `position` (a glide's start included, clamped as ApplyControls clamps), as settings of
/// `scene`; for sim::SubstepsForRange(least, most).
struct SettingRange {
  sim::SimParams least, most;
};
SettingRange SettingsAround(const Scene& scene, const sim::Timeline& timeline, double position);

/// Whether the timeline moves a control the substeps depend on (spring moduli, damping, friction).
bool MovesStability(const sim::Timeline& timeline);

}  // namespace flagsim
