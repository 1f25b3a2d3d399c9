#include "session.hpp"

#include "parameter_table.hpp"

namespace flagsim {

Session::Session(const Scene& scene)
    : initial_(scene),
      scene_(scene),
      simulation_(scene.sim, scene.wind, scene.seed),
      render_scene_(render::DefaultRenderScene(float(scene.sim.pole_height))) {}

std::string Session::ApplyWind(const sim::WindSettings& wind) {
  const std::string problem = ParameterTable::CheckWind(wind);
  if (!problem.empty()) return problem;
  scene_.wind = wind;
  simulation_.SetWind(wind);
  ++revision_;
  return "";
}

std::string Session::ApplyParams(const ParamChange& change) {
  if (change.assignments.size() > kMaxAssignments) {
    return "num_assignments: " + std::to_string(change.assignments.size()) +
           " is out of range; allowed 0 .. " + std::to_string(kMaxAssignments);
  }
  // Work on a copy; the session changes only if every assignment and the whole are valid.
  Scene next = change.reset_to_scene ? initial_ : scene_;
  std::string problems;
  for (const auto& [name, value] : change.assignments) {
    const std::string problem = ParameterTable::Get().Assign(name, value, &next);
    if (!problem.empty()) problems += (problems.empty() ? "" : "; ") + problem;
  }
  if (problems.empty()) problems = ParameterTable::CheckConsistency(next);
  if (!problems.empty()) return problems;

  if (next.sim.pole_height != scene_.sim.pole_height) {
    render_scene_ = render::DefaultRenderScene(float(next.sim.pole_height));
  }
  scene_ = next;
  simulation_.SetParams(scene_.sim);
  if (change.reset_to_scene) {
    sim::WindSettings wind = scene_.wind;
    wind.ramp_time = 0;  // back to the scene's wind at once
    simulation_.SetWind(wind);
    simulation_.RestartFlag();
  }
  ++revision_;
  return "";
}

bool Session::Step() {
  simulation_.Step();
  if (simulation_.params().integrator == scene_.sim.integrator) return false;
  scene_.sim.integrator = simulation_.params().integrator;
  return true;
}

std::string Session::ApplyCamera(const render::CameraMove& move) {
  if (move.operation == render::CameraMove::kReset) {
    scene_.camera = initial_.camera;
    ++revision_;
    return "";
  }
  const std::string problem = render::ApplyCameraMove(move, &scene_.camera);
  if (problem.empty()) ++revision_;
  return problem;
}

// state => flag mesh => frame
const render::Framebuffer& Session::RenderFrame(int threads) {
  const auto& state = simulation_.state();
  const auto& model = simulation_.model();
  render::UpdateFlagMesh(model.cols, model.rows, state.x.data(), state.y.data(), state.z.data(),
                         &render_scene_.meshes[0]);
  render::RenderOptions options;
  options.mode = scene_.service.shading;
  options.threads = threads;
  renderer_.Render(render_scene_, scene_.camera, options, &framebuffer_);
  return framebuffer_;
}

}  // namespace flagsim
