// The one table of settable parameters: name, unit, range, default, description, and how each
// reads and writes a Scene. It drives PARAM validation, scene files, the PARAMS message and
// `flagctl params`, so the four never disagree.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "server/scene/scene.hpp"

namespace flagsim {

enum class ParameterKind { kReal, kInteger, kBoolean, kChoice };

struct Parameter {
  std::string name;  ///< e.g. "stiffness"
  std::string unit;  ///< SI unit, "" for pure numbers, names and switches
  ParameterKind kind = ParameterKind::kReal;
  double min_value = 0;  ///< inclusive; for kChoice an index range
  double max_value = 0;
  std::vector<std::string> choices;  ///< kChoice: the names, value = index
  /// Where the server may choose this setting (integrator, cols, rows): the switch that says it
  /// does. Assign takes "auto" to set the switch, and a value to clear it; the value always holds
  /// the setting in force, whoever chose it.
  bool ModelSettings::*auto_switch = nullptr;
  /// Whether a keyframe may set it: a continuous coefficient of the forces, which a step can
  /// change in place (server/scene/scene_timeline.hpp).
  bool animatable = false;
  std::string description;
  std::function<double(const Scene&)> get;
  std::function<void(Scene&, double)> set;

  double default_value() const { return get(Scene{}); }
  /// The value as `flagctl set` takes it back: "1500", "true", "symplectic_euler".
  std::string Format(double value) const;
  /// "1 .. 100000 N/m", "true or false", "one of: a, b".
  std::string AllowedText() const;
};

class ParameterTable {
 public:
  static const ParameterTable& Get();

  const std::vector<Parameter>& parameters() const { return parameters_; }
  const Parameter* Find(const std::string& name) const;

  /// Parses `text` for parameter `name` and, if it is allowed, writes it into `scene`.
  /// Returns "" on success, else a reason naming the parameter and what is allowed; `scene` is
  /// then unchanged.
  std::string Assign(const std::string& name, const std::string& text, Scene* scene) const;

  /// Checks rules that join several parameters. Returns "" or the reason.
  static std::string CheckConsistency(const Scene& scene);

  /// What auto settles at once when the settings change: with integrator=auto, an integrator that
  /// would need more than sim::kMaxSubsteps substeps gives way to xpbd, stable at any step, until
  /// auto's next decision (server/service/model_governor.hpp). Call before CheckConsistency.
  static void SettleAutoModel(Scene* scene);

  static constexpr double kMaxWindSpeed = 60.0;  ///< m/s
  static constexpr double kMaxGust = 1.0;        ///< fraction of the wind speed
  static constexpr double kMaxRampTime = 60.0;   ///< s
  /// Checks a wind setting (WIND command or scene file). Returns "" or the reason.
  static std::string CheckWind(const sim::WindSettings& wind);

 private:
  ParameterTable();
  std::vector<Parameter> parameters_;
};

}  // namespace flagsim
