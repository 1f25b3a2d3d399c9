#include "server/scene/scene_timeline.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "common/printable_text.hpp"
#include "server/render/camera_moves.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/sim/integrator.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim {
namespace {

using Limits = TimelineLimits;

/// The parameters the substeps depend on: what the frequency bound reads.
constexpr const char* kStabilityNames[] = {"stiffness", "shear_stiffness", "bending_stiffness", "damping",
                                           "friction"};

std::string Number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);  // shortest exact
  return std::string(buffer, result.ptr);
}

/// "" if low <= value <= high, else "field: value is out of range (or not a finite number);
/// allowed low .. high unit".
std::string CheckRange(const std::string& field, double value, double low, double high,
                       const std::string& unit) {
  if (value >= low && value <= high) return "";
  const std::string what = std::isfinite(value) ? " is out of range" : " is not a finite number";
  return field + ": " + Number(value) + what + "; allowed " + Number(low) + " .. " + Number(high) + unit;
}

std::string List(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

using sim::Length;

/// "" or what is wrong with the parameters of key `what`.
std::string CheckParameters(const std::vector<sim::ParameterControl>& parameters, const std::string& what) {
  if (parameters.size() > Limits::kMaxKeyParameters) {
    return what + ".parameters: " + std::to_string(parameters.size()) + " of them; allowed at most " +
           std::to_string(Limits::kMaxKeyParameters);
  }
  for (size_t i = 0; i < parameters.size(); ++i) {
    const sim::ParameterControl& each = parameters[i];
    const Parameter* parameter = ParameterTable::Get().Find(each.name);
    if (parameter == nullptr) {
      return what + ".parameters: unknown parameter '" + PrintableText(each.name) +
             "'; animatable: " + List(AnimatableNames());
    }
    const std::string field = what + ".parameters." + each.name;
    if (!parameter->animatable) {
      return field +
             ": cannot be animated (grid, numerics, integers, choices and switches are set by "
             "PARAM); animatable: " +
             List(AnimatableNames());
    }
    for (size_t j = 0; j < i; ++j) {
      if (parameters[j].name == each.name) return field + ": set twice in one key";
    }
    const std::string unit = parameter->unit.empty() ? "" : " " + parameter->unit;
    const std::string problem =
        CheckRange(field, each.value, parameter->min_value, parameter->max_value, unit);
    if (!problem.empty()) return problem;
  }
  return "";
}

std::string CheckPoint(const std::string& field, const sim::Vec3& point) {
  const bool finite = std::isfinite(point[0]) && std::isfinite(point[1]) && std::isfinite(point[2]);
  if (finite && Length(point) <= render::CameraMove::kMaxDistance) return "";
  return field + ": allowed finite coordinates within " + Number(render::CameraMove::kMaxDistance) +
         " m of the origin";
}

/// "" or what is wrong with the camera of key `what`.
std::string CheckCamera(const sim::CameraControl& camera, const std::string& what) {
  for (const std::string& problem :
       {CheckPoint(what + ".camera.eye", camera.eye), CheckPoint(what + ".camera.target", camera.target),
        CheckRange(what + ".camera.fov", camera.fov, Limits::kMinFov, Limits::kMaxFov, " degrees")}) {
    if (!problem.empty()) return problem;
  }
  const sim::Vec3 gap{camera.target[0] - camera.eye[0], camera.target[1] - camera.eye[1],
                      camera.target[2] - camera.eye[2]};
  if (Length(gap) < Limits::kMinCameraGap) {
    return what + ".camera.target: allowed at least " + Number(Limits::kMinCameraGap) + " m from the eye";
  }
  return "";
}

/// Each name once, with the least low and the most high.
void Merge(const std::vector<sim::ParameterRange>& more, std::vector<sim::ParameterRange>* ranges) {
  for (const sim::ParameterRange& range : more) {
    const auto same = std::find_if(ranges->begin(), ranges->end(), [&range](const sim::ParameterRange& each) {
      return each.name == range.name;
    });
    if (same == ranges->end()) {
      ranges->push_back(range);
    } else {
      same->low = std::min(same->low, range.low);
      same->high = std::max(same->high, range.high);
    }
  }
}

/// The scene's settings with each range's low in `least` and high in `most`, clamped to the
/// table's ranges.
SettingRange Settings(const Scene& scene, const std::vector<sim::ParameterRange>& ranges) {
  Scene least, most;
  least.sim = most.sim = scene.sim;
  for (const sim::ParameterRange& range : ranges) {
    const Parameter* parameter = ParameterTable::Get().Find(range.name);
    if (parameter == nullptr || !parameter->animatable) continue;
    parameter->set(least, std::clamp(range.low, parameter->min_value, parameter->max_value));
    parameter->set(most, std::clamp(range.high, parameter->min_value, parameter->max_value));
  }
  return {least.sim, most.sim};
}

/// The timeline's extremes anywhere: every segment's, merged.
SettingRange SettingsAnywhere(const Scene& scene, const sim::Timeline& timeline) {
  std::vector<sim::ParameterRange> ranges;
  for (const sim::Keyframe& key : timeline.keys()) Merge(timeline.ParameterRanges(key.time), &ranges);
  Merge(timeline.ParameterRanges(timeline.position()), &ranges);  // a glide under way
  return Settings(scene, ranges);
}

/// "" or why the scene's integrator cannot take the settings the timeline reaches.
std::string CheckReach(const sim::Timeline& timeline, const Scene& scene) {
  if (!MovesStability(timeline)) return "";
  const SettingRange reach = SettingsAnywhere(scene, timeline);
  if (scene.sim.integrator == sim::IntegratorKind::kSeed && reach.most.forces.friction >= 1) {
    return "friction: the keys reach " + Number(reach.most.forces.friction) +
           "; the seed integrator reads friction as a fraction mu of the force; allowed 0 .. 1 "
           "(exclusive) with integrator=seed";
  }
  const int substeps = sim::SubstepsForRange(reach.least, reach.most);
  if (substeps <= sim::kMaxSubsteps) return "";
  return "keys: at their stiffest (stiffness up to " + Number(reach.most.forces.stiffness) +
         " N/m, damping down to " + Number(reach.least.forces.damping) + " N s/m) " +
         sim::IntegratorName(scene.sim.integrator) + " needs " + std::to_string(substeps) +
         " substeps per step; allowed at most " + std::to_string(sim::kMaxSubsteps) +
         ": soften the keys, damp them more, or choose an unconditionally stable integrator (xpbd)";
}

}  // namespace

std::vector<std::string> AnimatableNames() {
  std::vector<std::string> names;
  for (const Parameter& parameter : ParameterTable::Get().parameters()) {
    if (parameter.animatable) names.push_back(parameter.name);
  }
  return names;
}

std::string CheckTimelineTime(const std::string& field, double time) {
  return CheckRange(field, time, 0, Limits::kMaxTime, " s");
}

std::string CheckTimelineSpeed(const std::string& field, double speed) {
  if (speed > 0 && speed <= Limits::kMaxSpeed) return "";
  return field + ": " + Number(speed) + "; allowed above 0, up to " + Number(Limits::kMaxSpeed) +
         " timeline s per simulated s";
}

std::string SecondsText(double seconds) { return Number(seconds) + " s"; }

std::string KeyTimes(const sim::Timeline& timeline) {
  if (timeline.keys().empty()) return "none";
  std::vector<std::string> times;
  for (const sim::Keyframe& key : timeline.keys()) times.push_back(Number(key.time));
  return List(times) + " s";
}

std::string CheckKeyframe(const sim::Keyframe& key, const std::string& what) {
  std::string problem = CheckTimelineTime(what + ".time", key.time);
  if (!problem.empty()) return problem;
  const int law = static_cast<int>(key.law);
  if (law < 0 || law >= int(sim::ControlLawNames().size())) {
    return what + ".law: " + std::to_string(law) + " is not a law; allowed " + List(sim::ControlLawNames());
  }
  if (!key.wind && key.parameters.empty() && !key.camera) {
    return what + " sets nothing; allowed any of wind, parameters and camera";
  }
  if (key.wind) {
    problem = ParameterTable::CheckWind(sim::WindSettings{key.wind->velocity, key.wind->gust, 0});
    if (!problem.empty()) return what + ".wind." + problem;
  }
  problem = CheckParameters(key.parameters, what);
  if (problem.empty() && key.camera) problem = CheckCamera(*key.camera, what);
  return problem;
}

std::string CheckTimeline(const sim::Timeline& timeline, const Scene& scene) {
  const auto& keys = timeline.keys();
  if (keys.size() > Limits::kMaxKeys) {
    return "keys: " + std::to_string(keys.size()) + " of them; allowed at most " +
           std::to_string(Limits::kMaxKeys);
  }
  for (size_t i = 0; i < keys.size(); ++i) {
    const std::string problem = CheckKeyframe(keys[i], "keys[" + std::to_string(i) + "]");
    if (!problem.empty()) return problem;
  }
  std::string problem = CheckTimelineTime("position", timeline.position());
  if (problem.empty()) problem = CheckTimelineSpeed("speed", timeline.speed());
  return problem.empty() ? CheckReach(timeline, scene) : problem;
}

void ApplyControls(const sim::Controls& controls, Scene* scene) {
  if (controls.wind) {
    const double speed = Length(controls.wind->velocity);
    const double scale = speed > ParameterTable::kMaxWindSpeed ? ParameterTable::kMaxWindSpeed / speed : 1.0;
    for (int k = 0; k < 3; ++k) scene->wind.velocity[k] = controls.wind->velocity[k] * scale;
    scene->wind.gust = std::clamp(controls.wind->gust, 0.0, ParameterTable::kMaxGust);
    scene->wind.ramp_time = 0;
  }
  for (const sim::ParameterControl& each : controls.parameters) {
    const Parameter* parameter = ParameterTable::Get().Find(each.name);
    if (parameter == nullptr || !parameter->animatable) continue;
    parameter->set(*scene, std::clamp(each.value, parameter->min_value, parameter->max_value));
  }
  if (controls.camera) {
    const auto within = [](const sim::Vec3& point) -> Eigen::Vector3d {
      const double length = Length(point), most = render::CameraMove::kMaxDistance;
      return Eigen::Vector3d(point[0], point[1], point[2]) * (length > most ? most / length : 1.0);
    };
    const Eigen::Vector3d eye = within(controls.camera->eye), target = within(controls.camera->target);
    if ((target - eye).norm() >= Limits::kMinCameraGap) {
      scene->camera.eye = eye;
      scene->camera.target = target;
    }
    scene->camera.fov_y = std::clamp(controls.camera->fov, Limits::kMinFov, Limits::kMaxFov) * M_PI / 180;
  }
}

sim::Controls ControlsInForce(const Scene& scene, const sim::Timeline& timeline,
                              const sim::WindControl& wind_now) {
  const sim::Controls set = timeline.Evaluate(timeline.position());
  sim::Controls in_force;
  if (set.wind) in_force.wind = wind_now;
  for (const sim::ParameterControl& each : set.parameters) {
    if (const Parameter* parameter = ParameterTable::Get().Find(each.name)) {
      in_force.parameters.push_back({each.name, parameter->get(scene)});
    }
  }
  if (set.camera) {
    const render::Camera& camera = scene.camera;
    in_force.camera = sim::CameraControl{{camera.eye.x(), camera.eye.y(), camera.eye.z()},
                                         {camera.target.x(), camera.target.y(), camera.target.z()},
                                         camera.fov_y * 180 / M_PI};
  }
  return in_force;
}

SettingRange SettingsAround(const Scene& scene, const sim::Timeline& timeline, double position) {
  return Settings(scene, timeline.ParameterRanges(position));
}

bool MovesStability(const sim::Timeline& timeline) {
  for (const sim::Keyframe& key : timeline.keys()) {
    for (const char* name : kStabilityNames) {
      if (key.Parameter(name) != nullptr) return true;
    }
  }
  return false;
}

}  // namespace flagsim
