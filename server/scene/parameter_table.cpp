#include "server/scene/parameter_table.hpp"

#include <charconv>
#include <cmath>
#include <type_traits>

#include "common/printable_text.hpp"
#include "server/sim/integrator.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim {
namespace {

using sim::SimParams;

using sim::ForceCoefficients;

/// A parameter stored where the member pointers `path` lead from the scene:
/// scene.*path[0].*path[1]... It is animatable exactly when it is one of the forces'
/// coefficients, the fields Simulation::SetControls takes in place.
/// A parameter's row without its accessors.
Parameter Row(std::string name, std::string unit, ParameterKind kind, double min_value, double max_value,
              std::string description) {
  Parameter parameter;
  parameter.name = std::move(name);
  parameter.unit = std::move(unit);
  parameter.kind = kind;
  parameter.min_value = min_value;
  parameter.max_value = max_value;
  parameter.description = std::move(description);
  return parameter;
}

template <class... Members>
Parameter Make(std::string name, std::string unit, ParameterKind kind, double min_value, double max_value,
               std::string description, Members... path) {
  Parameter parameter = Row(std::move(name), std::move(unit), kind, min_value, max_value, std::move(description));
  parameter.animatable = (std::is_same_v<Members, double ForceCoefficients::*> || ...);
  parameter.get = [path...](const Scene& scene) { return static_cast<double>((scene.*....*path)); };
  parameter.set = [path...](Scene& scene, double value) {
    auto& field = (scene.*....*path);
    using Field = std::remove_reference_t<decltype(field)>;
    if constexpr (std::is_floating_point_v<Field>) {
      field = value;
    } else {
      field = static_cast<Field>(std::llround(value));
    }
  };
  return parameter;
}

template <class Field>
Parameter Real(std::string name, std::string unit, double min_value, double max_value,
               Field SimParams::*field, std::string description) {
  return Make(std::move(name), std::move(unit), ParameterKind::kReal, min_value, max_value,
              std::move(description), &Scene::sim, field);
}

/// One of the forces' coefficients: animatable.
Parameter Force(std::string name, std::string unit, double min_value, double max_value,
                double ForceCoefficients::*field, std::string description) {
  return Make(std::move(name), std::move(unit), ParameterKind::kReal, min_value, max_value,
              std::move(description), &Scene::sim, &SimParams::forces, field);
}

Parameter Integer(std::string name, double min_value, double max_value, int SimParams::*field,
                  std::string description) {
  return Make(std::move(name), "", ParameterKind::kInteger, min_value, max_value, std::move(description),
              &Scene::sim, field);
}

/// A setting the server may choose: "auto" sets `auto_switch`, a value clears it.
Parameter Chosen(Parameter parameter, bool ModelSettings::*auto_switch) {
  parameter.auto_switch = auto_switch;
  return parameter;
}

std::string FormatNumber(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);  // shortest exact
  return std::string(buffer, result.ptr);
}

/// Reads all of `text` as a number; false if anything is left over or nothing was read.
bool ParseNumber(const std::string& text, double* value) {
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end;
}

bool ParseBoolean(const std::string& text, double* value) {
  for (const char* yes : {"true", "1", "on", "yes"}) {
    if (text == yes) return *value = 1, true;
  }
  for (const char* no : {"false", "0", "off", "no"}) {
    if (text == no) return *value = 0, true;
  }
  return false;
}

/// Parses `text` as a value of `parameter`; "" or what is wrong with it.
std::string Parse(const Parameter& parameter, const std::string& text, double* value) {
  switch (parameter.kind) {
    case ParameterKind::kBoolean:
      return ParseBoolean(text, value) ? "" : "'" + PrintableText(text) + "' is not a switch";
    case ParameterKind::kChoice:
      for (size_t i = 0; i < parameter.choices.size(); ++i) {
        if (text == parameter.choices[i]) return *value = double(i), "";
      }
      return "'" + PrintableText(text) + "' is not a known name";
    case ParameterKind::kInteger: {
      long long integer = 0;
      const char* end = text.data() + text.size();
      const auto result = std::from_chars(text.data(), end, integer);
      if (result.ec != std::errc() || result.ptr != end)
        return "'" + PrintableText(text) + "' is not an integer";
      *value = double(integer);
      return "";
    }
    case ParameterKind::kReal:
      if (!ParseNumber(text, value)) return "'" + PrintableText(text) + "' is not a number";
      if (!std::isfinite(*value)) return "'" + PrintableText(text) + "' is not a finite number";
      return "";
  }
  return "unknown kind";
}

}  // namespace

std::string Parameter::Format(double value) const {
  switch (kind) {
    case ParameterKind::kBoolean:
      return value != 0 ? "true" : "false";
    case ParameterKind::kChoice: {
      const auto index = static_cast<size_t>(value);
      return index < choices.size() ? choices[index] : FormatNumber(value);
    }
    case ParameterKind::kInteger:
    case ParameterKind::kReal:
      break;
  }
  return FormatNumber(value);
}

std::string Parameter::AllowedText() const {
  switch (kind) {
    case ParameterKind::kBoolean:
      return "true or false";
    case ParameterKind::kChoice: {
      std::string text = "one of:";
      for (size_t i = 0; i < choices.size(); ++i) text += (i ? ", " : " ") + choices[i];
      return text + (auto_switch ? ", auto" : "");
    }
    case ParameterKind::kInteger:
    case ParameterKind::kReal:
      break;
  }
  return FormatNumber(min_value) + " .. " + FormatNumber(max_value) + (unit.empty() ? "" : " " + unit) +
         (auto_switch ? ", or auto" : "");
}

ParameterTable::ParameterTable() {
  parameters_ = {
      Chosen(Integer("cols", 2, 512, &SimParams::cols,
                     "nodes along the flag; a number rebuilds the flag; auto (or rows=auto): the server "
                     "chooses the grid for the picture, at the flag's cols : rows"),
             &ModelSettings::auto_grid),
      Chosen(Integer("rows", 2, 512, &SimParams::rows, "nodes down the flag; a number rebuilds the flag; auto: as cols"),
             &ModelSettings::auto_grid),
      Real("width", "m", 0.1, 10, &SimParams::width, "flag length along its rows (fly)"),
      Real("height", "m", 0.1, 10, &SimParams::height, "flag length down its columns (hoist)"),
      Real("mass", "kg", 0.001, 100, &SimParams::mass, "mass of the whole flag"),
      Real("pole_height", "m", 0.5, 50, &SimParams::pole_height, "height of the pole's top"),
      Force("stiffness", "N/m", 1, 100000, &ForceCoefficients::stiffness,
            "structural stretch modulus of the sheet (springs to row and column neighbours)"),
      Force("shear_stiffness", "N/m", 0, 100000, &ForceCoefficients::shear_stiffness,
            "shear modulus of the sheet (diagonal springs)"),
      Force("bending_stiffness", "N m", 0, 1, &ForceCoefficients::bending_stiffness,
            "bending stiffness (flexural rigidity) of the sheet, on its curvature"),
      Force("damping", "N s/m", 0, 100, &ForceCoefficients::damping, "damping along every spring"),
      Real("compression", "", 0, 1, &SimParams::compression,
           "compressive stiffness of structural and shear springs as a fraction of their stiffness"),
      Real("imperfection", "m", 0, 0.05, &SimParams::imperfection,
           "largest out-of-plane departure of the rest state from a flat sheet, which buckling grows "
           "from; a change rebuilds the flag"),
      Real("pole_radius", "m", 0.005, 0.5, &SimParams::pole_radius,
           "radius of the pole: a cylinder the cloth cannot enter, the hoist edge on its surface; a change "
           "rebuilds the flag"),
      Real("pole_friction", "", 0, 2, &SimParams::pole_friction,
           "Coulomb friction coefficient of the cloth on the pole and the ground"),
      Real("thickness", "m", 0.0005, 0.05, &SimParams::thickness,
           "the least distance the cloth keeps from itself, the pole and the ground"),
      Make("self_collision", "", ParameterKind::kBoolean, 0, 1, "the cloth does not pass through itself",
           &Scene::sim, &SimParams::self_collision),
      Force("friction", "1/s", 0, 100, &ForceCoefficients::friction,
            "air friction -friction m v per node (seed integrator: fraction mu of F, below 1)"),
      Force("wind_coefficient", "N s/m^3", 0, 100, &ForceCoefficients::wind_coefficient,
            "C in the face wind force C A n (n . w)"),
      Make("relative_wind", "", ParameterKind::kBoolean, 0, 1,
           "wind relative to the moving cloth (w - v_face) instead of w", &Scene::sim,
           &SimParams::relative_wind),
      Force("gravity", "m/s^2", 0, 100, &ForceCoefficients::gravity, "downward acceleration of gravity"),
      Real("dt", "s", 1e-5, 0.05, &SimParams::dt,
           "step: commands apply between steps; explicit integrators substep for stability"),
      Chosen(Make("integrator", "", ParameterKind::kChoice, 0, double(sim::IntegratorNames().size() - 1),
                  "time integrator; auto: the server chooses it, its substeps and iterations", &Scene::sim,
                  &SimParams::integrator),
             &ModelSettings::auto_integrator),
      Integer("substeps", 0, sim::kMaxSubsteps, &SimParams::substeps,
              "substeps per step; 0: chosen from the integrator's stability limit"),
      Integer("solver_iterations", 1, 1000, &SimParams::solver_iterations,
              "iterations per step of the xpbd and projective integrators"),
      Real("solver_tolerance", "", 1e-8, 0.5, &SimParams::solver_tolerance,
           "implicit_euler: conjugate gradient stops at this residual relative to the right-hand side"),
      Integer("threads", 1, 64, &SimParams::threads,
              "worker threads for the step and the frames (no more run at once than the machine has "
              "cores, nor in flagd than other processes leave free); the step shares the flag among "
              "them from 4096 nodes a thread"),
      Make("auto_integrator", "", ParameterKind::kBoolean, 0, 1,
           "the server chooses the integrator (integrator=auto); a named integrator sets this false",
           &Scene::model, &ModelSettings::auto_integrator),
      Make("auto_grid", "", ParameterKind::kBoolean, 0, 1,
           "the server chooses the grid (cols=auto); a number of cols or rows sets this false", &Scene::model,
           &ModelSettings::auto_grid),
      Make("error_budget", "px", ParameterKind::kReal, 0.05, 100,
           "screen_error auto keeps the flag within, at the camera and image size in force", &Scene::model,
           &ModelSettings::error_budget),
      Make("cost_budget", "", ParameterKind::kReal, 0.01, 64,
           "CPU seconds per simulated second auto may spend stepping the flag (by the cost model; 1: one "
           "core in real time)", &Scene::model, &ModelSettings::cost_budget),
      Make("state_rate", "Hz", ParameterKind::kReal, 1, 1000, "STATE messages per second of simulated time",
           &Scene::service, &ServiceSettings::state_rate),
      Make("frame_rate", "Hz", ParameterKind::kReal, 0, 120,
           "frames drawn and streamed per second of simulated time; 0: none", &Scene::service,
           &ServiceSettings::frame_rate),
      Make("time_scale", "", ParameterKind::kReal, 0.1, 4,
           "simulated seconds per wall-clock second (1: real time); frames still come at frame_rate "
           "on the wall clock; a reset leaves it", &Scene::service, &ServiceSettings::time_scale),
      Make("shading", "", ParameterKind::kChoice, 0, double(render::ShadingModeNames().size() - 1),
           "how frames are shaded", &Scene::service, &ServiceSettings::shading),
      Make("design", "", ParameterKind::kChoice, 0, double(render::FlagDesignNames().size() - 1),
           "the flag's design, a built-in one by name (a scene file: design = \"NAME\" at its top level)",
           &Scene::service, &ServiceSettings::design),
      Make("antialias", "", ParameterKind::kChoice, 0, double(render::AntialiasingNames().size() - 1),
           "smooth edges: samples per pixel (msaa2, msaa4, msaa8), each pixel shaded once; off: one",
           &Scene::service, &ServiceSettings::antialias),
  };
  // The names of each choice parameter.
  for (Parameter& parameter : parameters_) {
    if (parameter.name == "integrator") parameter.choices = sim::IntegratorNames();
    if (parameter.name == "shading") parameter.choices = render::ShadingModeNames();
    if (parameter.name == "design") parameter.choices = render::FlagDesignNames();
    if (parameter.name == "antialias") parameter.choices = render::AntialiasingNames();
  }
}

const ParameterTable& ParameterTable::Get() {
  static const ParameterTable table;
  return table;
}

const Parameter* ParameterTable::Find(const std::string& name) const {
  for (const Parameter& parameter : parameters_) {
    if (parameter.name == name) return &parameter;
  }
  return nullptr;
}

std::string ParameterTable::Assign(const std::string& name, const std::string& text, Scene* scene) const {
  const Parameter* parameter = Find(name);
  if (parameter == nullptr && name == "bend_stiffness") {
    return "bend_stiffness (N/m, springs between nodes two apart) is no longer a parameter: the sheet "
           "bends by bending_stiffness, in N m, allowed " + Find("bending_stiffness")->AllowedText();
  }
  if (parameter == nullptr) {
    std::string known;
    for (const Parameter& each : parameters_) known += (known.empty() ? "" : ", ") + each.name;
    return "unknown parameter '" + PrintableText(name) + "'; known: " + known;
  }
  if (parameter->auto_switch && text == "auto") {
    scene->model.*parameter->auto_switch = true;
    return "";
  }
  double value = 0;
  std::string problem = Parse(*parameter, text, &value);
  if (problem.empty() && (value < parameter->min_value || value > parameter->max_value)) {
    problem = PrintableText(text) + " is out of range";
  }
  if (!problem.empty()) return name + ": " + problem + "; allowed " + parameter->AllowedText();
  parameter->set(*scene, value);
  if (parameter->auto_switch) scene->model.*parameter->auto_switch = false;
  return "";
}

void ParameterTable::SettleAutoModel(Scene* scene) {
  if (scene->model.auto_integrator && sim::SubstepsFor(scene->sim) > sim::kMaxSubsteps) {
    scene->sim.integrator = sim::IntegratorKind::kXpbd;
  }
}

std::string ParameterTable::CheckConsistency(const Scene& scene) {
  if (scene.sim.integrator == sim::IntegratorKind::kSeed && scene.sim.forces.friction >= 1) {
    return "friction: the seed integrator reads friction as a fraction mu of the force; allowed "
           "0 .. 1 (exclusive) with integrator=seed";
  }
  // An explicit integrator on a stiff, fine or undamped flag may need more substeps than any
  // server can take in time: say so rather than stall.
  const int substeps = sim::SubstepsFor(scene.sim);
  if (substeps > sim::kMaxSubsteps) {
    return "integrator: " + sim::IntegratorName(scene.sim.integrator) + " needs " + std::to_string(substeps) +
           (scene.sim.substeps > 0 ? " substeps per step (as set)"
                                   : " substeps per step to stay stable on this flag") +
           "; allowed at most " + std::to_string(sim::kMaxSubsteps) +
           ": raise damping, lower stiffness, coarsen the grid, or choose an unconditionally stable "
           "integrator (xpbd)";
  }
  return "";
}

std::string ParameterTable::CheckWind(const sim::WindSettings& wind) {
  const char* axis[3] = {"x", "y", "z"};
  double speed_squared = 0;
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(wind.velocity[k])) {
      return std::string("velocity.") + axis[k] + ": " + FormatNumber(wind.velocity[k]) +
             " is not a finite number; allowed a speed up to " + FormatNumber(kMaxWindSpeed) + " m/s";
    }
    speed_squared += wind.velocity[k] * wind.velocity[k];
  }
  if (std::sqrt(speed_squared) > kMaxWindSpeed) {
    return "velocity: speed " + FormatNumber(std::sqrt(speed_squared)) +
           " m/s is out of range; allowed 0 .. " + FormatNumber(kMaxWindSpeed) + " m/s";
  }
  if (!(wind.gust >= 0 && wind.gust <= kMaxGust)) {
    return "gust: " + FormatNumber(wind.gust) + " is out of range; allowed 0 .. " + FormatNumber(kMaxGust);
  }
  if (!(wind.ramp_time >= 0 && wind.ramp_time <= kMaxRampTime)) {
    return "ramp_time: " + FormatNumber(wind.ramp_time) + " is out of range; allowed 0 .. " +
           FormatNumber(kMaxRampTime) + " s";
  }
  return "";
}

}  // namespace flagsim
