#include "server/service/session.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "server/render/camera_on_flag.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/scene/scene_timeline.hpp"

namespace flagsim {
namespace {

/// The design's image after assignments to `scene` (from `before`): dropped with a built-in
/// design, whose aspect the width goes back to if it follows the design; required by
/// design=image. "" or what is wrong.
std::string FollowDesign(const ServiceSettings& before, Scene* scene) {
  ServiceSettings& service = scene->service;
  if (service.design != render::FlagDesign::kImage) {
    if (before.design == render::FlagDesign::kImage && service.width_follows_design)
      scene->sim.width = std::clamp(scene->sim.height * render::kBuiltInDesignAspect, 0.1, 10.0);
    service.design_file.reset();
    return "";
  }
  if (service.design_file) return "";
  std::string built_in;
  for (const std::string& name : render::FlagDesignNames())
    if (name != "image") built_in += (built_in.empty() ? "" : ", ") + name;
  return "design: image shows a person's own image, which comes as a file (flagctl design FILE); "
         "by name, allowed: " +
         built_in;
}

/// The scene as a playing timeline starts it: its controls at its position applied.
Scene AtTimelineStart(Scene scene) {
  if (scene.timeline.playing()) ApplyControls(scene.timeline.Evaluate(scene.timeline.position()), &scene);
  return scene;
}

/// `key` with what `edit` changes: its controls replace the key's, the key moves to its time.
sim::Keyframe Changed(sim::Keyframe key, const TimelineEdit& edit) {
  key.time = edit.key.time;
  if (!edit.keep_law) key.law = edit.key.law;
  if (edit.key.wind) key.wind = edit.key.wind;
  if (edit.key.camera) key.camera = edit.key.camera;
  for (const sim::ParameterControl& parameter : edit.key.parameters) {
    const auto same =
        std::find_if(key.parameters.begin(), key.parameters.end(),
                     [&parameter](const sim::ParameterControl& each) { return each.name == parameter.name; });
    if (same == key.parameters.end()) {
      key.parameters.push_back(parameter);
    } else {
      same->value = parameter.value;
    }
  }
  return key;
}

std::string NoKeyAt(const std::string& field, double time, const sim::Timeline& timeline) {
  return field + ": no key at " + SecondsText(time) + "; keys at " + KeyTimes(timeline);
}

/// Applies `edit` to `timeline`; "" or what is wrong with the edit itself (the timeline as a
/// whole is checked after).
std::string Edit(const TimelineEdit& edit, sim::Timeline* timeline) {
  std::string problem;
  switch (edit.operation) {
    case TimelineEdit::kAdd:
      problem = CheckKeyframe(edit.key, "key");
      if (problem.empty()) timeline->Add(edit.key);
      return problem;
    case TimelineEdit::kChange: {
      const sim::Keyframe* key = timeline->Find(edit.time);
      if (key == nullptr) return NoKeyAt("time", edit.time, *timeline);
      const sim::Keyframe changed = Changed(*key, edit);
      problem = CheckKeyframe(changed, "key");
      if (problem.empty() && changed.time != edit.time && timeline->Find(changed.time) != nullptr) {
        problem = "key.time: a key is at " + SecondsText(changed.time) + " already; remove it first";
      }
      if (!problem.empty()) return problem;
      timeline->Remove(edit.time);
      timeline->Add(changed);
      return "";
    }
    case TimelineEdit::kRemove:
      return timeline->Remove(edit.time) ? "" : NoKeyAt("time", edit.time, *timeline);
    case TimelineEdit::kClear:
      timeline->Clear();
      return "";
    case TimelineEdit::kPlay:
      if (timeline->keys().empty()) return "operation: play with no keys; add one first (keyframe add)";
      timeline->Play();
      return "";
    case TimelineEdit::kPause:
      timeline->Pause();
      return "";
    case TimelineEdit::kSeek:
      problem = CheckTimelineTime("time", edit.time);
      if (problem.empty()) timeline->Seek(edit.time);
      return problem;
    case TimelineEdit::kLoop:
      timeline->SetLoop(edit.loop);
      return "";
    case TimelineEdit::kSpeed:
      problem = CheckTimelineSpeed("speed", edit.speed);
      if (problem.empty()) timeline->SetSpeed(edit.speed);
      return problem;
  }
  return "operation: unknown";
}

/// Whether `edit` may make the controls of a playing timeline jump.
bool MayJump(const TimelineEdit& edit, bool was_playing) {
  switch (edit.operation) {
    case TimelineEdit::kAdd:
    case TimelineEdit::kChange:
    case TimelineEdit::kRemove:
    case TimelineEdit::kSeek:
      return true;
    case TimelineEdit::kPlay:
      return !was_playing;
    default:
      return false;
  }
}

/// The flag of `scene` at time 0: flat at rest, or, when the scene settles, as it hangs after
/// scene.settle s of its own physics and wind. Those steps are not the session's: the clock and
/// the wind start again at 0 from the drape, so a replay resumes from the start's checkpoint.
FlagSimulation StartingSimulation(const Scene& scene) {
  FlagSimulation settling(scene.sim, scene.wind, scene.seed);
  if (scene.settle <= 0) return settling;
  while (settling.state().time < scene.settle) settling.Step();
  sim::SimulationSnapshot<float> start = settling.Snapshot();
  start.state.time = 0;
  start.state.step = 0;
  start.wind = sim::WindField(scene.wind, scene.seed).State();
  start.carried = {};  // a fresh start from the drape: nothing carried from the settling
  return FlagSimulation(start);
}

}  // namespace

Session::Session(const Scene& scene)
    : initial_(scene), scene_(AtTimelineStart(scene)), simulation_(StartingSimulation(scene_)) {}

Session::Session(const SessionSnapshot& snapshot)
    : initial_(snapshot.initial),
      scene_(snapshot.scene),
      simulation_(snapshot.simulation),
      substeps_segment_(snapshot.timeline_segment),
      substeps_fixed_(snapshot.substeps_fixed) {}

SessionSnapshot Session::Snapshot() const {
  return {initial_, scene_, simulation_.Snapshot(), substeps_segment_, substeps_fixed_};
}

std::string Session::ApplyWind(const sim::WindSettings& wind) {
  const std::string problem = ParameterTable::CheckWind(wind);
  if (!problem.empty()) return problem;
  scene_.wind = wind;
  simulation_.SetWind(wind);
  ++revision_;
  return "";
}

std::string Session::ApplyParams(const ParamChange& change) { return Change(change, nullptr); }

std::string Session::ApplyDesign(const DesignFilePtr& file) {
  ParamChange change;
  change.assignments = {{"design", "image"}};
  if (scene_.service.width_follows_design) {
    char width[32];
    std::snprintf(width, sizeof(width), "%.17g", file->WidthFor(scene_.sim.height));
    change.assignments.emplace_back("width", width);
  }
  return Change(change, file);
}

std::string Session::Change(const ParamChange& change, const DesignFilePtr& image) {
  if (change.assignments.size() > kMaxAssignments) {
    return "num_assignments: " + std::to_string(change.assignments.size()) +
           " is out of range; allowed 0 .. " + std::to_string(kMaxAssignments);
  }
  // Work on a copy; the session changes only if every assignment and the whole are valid.
  Scene next = change.reset_to_scene ? AtTimelineStart(initial_) : scene_;
  // A reset restarts the physics; the camera is the viewer's and has a reset of its own, and
  // the clock's speed is the viewer's too.
  if (change.reset_to_scene) {
    next.camera = scene_.camera;
    next.service.time_scale = scene_.service.time_scale;
  }
  std::string problems;
  for (const auto& [name, value] : change.assignments) {
    const std::string problem = ParameterTable::Get().Assign(name, value, &next);
    if (!problem.empty()) problems += (problems.empty() ? "" : "; ") + problem;
    if (name == "width" && !image) next.service.width_follows_design = false;  // a person set it
  }
  if (image) next.service.design_file = image;
  const std::string design_problem = FollowDesign(scene_.service, &next);
  if (!design_problem.empty()) problems += (problems.empty() ? "" : "; ") + design_problem;
  ParameterTable::SettleAutoModel(&next);
  if (problems.empty()) problems = ParameterTable::CheckConsistency(next);
  if (problems.empty() && !change.reset_to_scene) {  // the keys must suit the new settings too
    const std::string problem = CheckTimeline(next.timeline, next);
    if (!problem.empty()) problems = "timeline: " + problem;
  }
  if (!problems.empty()) return problems;

  scene_ = next;
  simulation_.SetParams(scene_.sim);
  substeps_segment_ = kNoSegment;  // SetParams chose substeps for the settings as they are
  geomorph_.reset();
  if (change.reset_to_scene) {
    sim::WindSettings wind = scene_.wind;
    wind.ramp_time = 0;  // back to the scene's wind at once
    simulation_.SetWind(wind);
    if (scene_.settle > 0) {
      simulation_.RestartFlag(StartingSimulation(scene_).state());  // the scene's drape again
    } else {
      simulation_.RestartFlag();
    }
  }
  ++revision_;
  return "";
}

std::string Session::ApplyModel(const ModelSwitch& model) {
  const int kinds = int(sim::IntegratorNames().size());
  if (int(model.integrator) < 0 || int(model.integrator) >= kinds) {
    return "integrator: " + std::to_string(int(model.integrator)) + " is not an integrator; allowed 0 .. " +
           std::to_string(kinds - 1);
  }
  if (!scene_.model.auto_integrator && !scene_.model.auto_grid) {
    return "model: integrator and grid are both set; auto chooses neither (integrator=auto, cols=auto)";
  }
  Scene next = scene_;
  if (next.model.auto_integrator) {
    next.sim.integrator = model.integrator;
    next.sim.solver_iterations = model.solver_iterations;
  }
  if (next.model.auto_grid) {
    next.sim.cols = model.cols;
    next.sim.rows = model.rows;
  }
  // Each value as the parameter table allows it.
  for (const char* name : {"cols", "rows", "solver_iterations"}) {
    const Parameter& parameter = *ParameterTable::Get().Find(name);
    const double value = parameter.get(next);
    if (value < parameter.min_value || value > parameter.max_value) {
      return std::string(name) + ": " + parameter.Format(value) + " is out of range; allowed " +
             parameter.Format(parameter.min_value) + " .. " + parameter.Format(parameter.max_value);
    }
  }
  const std::string problem = ParameterTable::CheckConsistency(next);
  if (!problem.empty()) return problem;

  const bool regrid = next.sim.cols != scene_.sim.cols || next.sim.rows != scene_.sim.rows;
  const bool coarser = regrid && next.sim.cols * next.sim.rows < scene_.sim.cols * scene_.sim.rows;
  sim::ClothModel<float> fine;
  sim::ClothState<float> fine_state;
  if (coarser) {
    fine = simulation_.model();
    fine_state = simulation_.state();
  }
  scene_ = next;
  if (regrid) simulation_.Regrid(scene_.sim.cols, scene_.sim.rows);
  simulation_.SetParams(scene_.sim);
  substeps_segment_ = kNoSegment;  // SetParams chose substeps for the model as it is
  geomorph_.reset();
  if (coarser) geomorph_.emplace(fine, fine_state, simulation_.model(), simulation_.state());
  ++revision_;
  return "";
}

const Geomorph* Session::geomorph() const {
  if (!geomorph_ || !geomorph_->Blends(simulation_.model(), simulation_.state().time)) return nullptr;
  return &*geomorph_;
}

std::string Session::ApplyTime(const TimeControl& control) {
  switch (control.operation) {
    case TimeControl::kPause:
    case TimeControl::kResume:
      paused_ = control.operation == TimeControl::kPause;
      steps_owed_ = 0;
      return "";
    case TimeControl::kStep:
      if (control.steps < 1 || control.steps > kMaxStepsOwed - steps_owed_) {
        return "steps: " + std::to_string(control.steps) + " is out of range; allowed 1 .. " +
               std::to_string(kMaxStepsOwed - steps_owed_) +
               (steps_owed_ > 0 ? " (" + std::to_string(steps_owed_) + " still owed)" : "");
      }
      paused_ = true;
      steps_owed_ += control.steps;
      return "";
  }
  return "operation: unknown";
}

bool Session::Step() {
  if (steps_owed_ > 0) --steps_owed_;
  if (scene_.timeline.playing()) FollowTimeline();
  simulation_.Step();
  if (simulation_.params().integrator == scene_.sim.integrator) return false;
  scene_.sim.integrator = simulation_.params().integrator;
  substeps_segment_ = kNoSegment;  // the guard's integrator chose its own
  return true;
}

// position => controls => scene (within limits) => simulation (light path); position += speed dt
void Session::FollowTimeline() {
  ApplyTimelineControls();
  scene_.timeline.Advance(scene_.sim.dt);
}

// What the keys set at the timeline's position: wind, parameters and camera, with substeps
// fixed for the segment.
void Session::ApplyTimelineControls() {
  const sim::Timeline& timeline = scene_.timeline;
  const double position = timeline.position();
  if (timeline.SegmentAt(position) != substeps_segment_) FixSubsteps(position);
  const render::Camera camera = scene_.camera;
  ApplyControls(timeline.Evaluate(position), &scene_);
  simulation_.SetControls(scene_.sim.forces, scene_.wind);
  if (scene_.camera.eye != camera.eye || scene_.camera.target != camera.target ||
      scene_.camera.fov_y != camera.fov_y) {
    ++revision_;
  }
}

// The segment's least and most settings => substeps stable for all between, fixed till it ends.
void Session::FixSubsteps(double position) {
  substeps_segment_ = scene_.timeline.SegmentAt(position);
  if (!MovesStability(scene_.timeline)) {
    if (std::exchange(substeps_fixed_, false)) simulation_.SetSubsteps(sim::SubstepsFor(scene_.sim));
    return;
  }
  const SettingRange range = SettingsAround(scene_, scene_.timeline, position);
  simulation_.SetSubsteps(sim::SubstepsForRange(range.least, range.most));
  substeps_fixed_ = true;
}

sim::WindControl Session::WindNow() const {
  const double time = simulation_.state().time;
  return {simulation_.wind().Mean(time), simulation_.wind().Gust(time)};
}

std::string Session::ApplyTimeline(const TimelineEdit& edit) {
  sim::Timeline next = scene_.timeline;
  std::string problem = Edit(edit, &next);
  if (problem.empty()) problem = CheckTimeline(next, scene_);
  if (!problem.empty()) return problem;
  if (next.playing() && MayJump(edit, scene_.timeline.playing())) {
    next.StartGlide(ControlsInForce(scene_, next, WindNow()));
  }
  scene_.timeline = std::move(next);
  substeps_segment_ = kNoSegment;
  // Scrubbing a paused timeline previews it: what the keys set where it now stands.
  if (edit.operation == TimelineEdit::kSeek && !scene_.timeline.playing() &&
      !scene_.timeline.keys().empty()) {
    ApplyTimelineControls();
  }
  return "";
}

std::string Session::ApplyCamera(const render::CameraMove& move) {
  if (move.operation == render::CameraMove::kReset) {
    scene_.camera = initial_.camera;
    ++revision_;
    return "";
  }
  const std::string problem = render::AimsAtTheFlag(move.operation)
                                  ? render::ApplyFlagCameraMove(move, FlagSurfaceNow(), &scene_.camera)
                                  : render::ApplyCameraMove(move, &scene_.camera);
  if (problem.empty()) ++revision_;
  return problem;
}

// The nodes as the state has them: what the flag-aware camera moves aim at and stop short of.
render::FlagSurface Session::FlagSurfaceNow() const {
  const sim::ClothState<float>& state = simulation_.state();
  render::FlagSurface flag;
  flag.cols = simulation_.params().cols;
  flag.rows = simulation_.params().rows;
  flag.nodes.reserve(state.num_nodes());
  for (int i = 0; i < state.num_nodes(); ++i) flag.nodes.emplace_back(state.x[i], state.y[i], state.z[i]);
  return flag;
}

}  // namespace flagsim
