#include "server/service/frame_painter.hpp"

#include "server/service/message_builders.hpp"

namespace flagsim {

FrameInput FrameInput::Of(const Session& session, int64_t utime) {
  const auto& state = session.simulation().state();
  const auto& model = session.simulation().model();
  FrameInput input;
  if (const Geomorph* morph = session.geomorph()) {  // just coarsened: the finer grid, fading
    input.cols = morph->cols();
    input.rows = morph->rows();
    morph->Draw(model, state, &input.x, &input.y, &input.z);
  } else {
    input.cols = model.cols;
    input.rows = model.rows;
    input.x = state.x;
    input.y = state.y;
    input.z = state.z;
  }
  input.camera = session.scene().camera;
  input.shading = session.scene().service.shading;
  input.design = session.scene().service.design;
  input.design_file = session.scene().service.design_file;
  input.antialias = session.scene().service.antialias;
  input.pole_height = session.scene().sim.pole_height;
  input.pole_radius = session.scene().sim.pole_radius;
  input.info = MakeFrameInfo(session, utime);
  return input;
}

// copied state => smooth surface, refined for the picture (the grid itself in wireframe) =>
// flag mesh => frame
const render::Framebuffer& FramePainter::Paint(const FrameInput& input, int threads) {
  if (input.pole_height != pole_height_ || input.pole_radius != pole_radius_ || input.design != design_ ||
      input.design_file != design_file_) {
    scene_ = render::DefaultRenderScene(float(input.pole_height), float(input.pole_radius), input.design);
    if (input.design_file) scene_.pattern = input.design_file->texture;
    pole_height_ = input.pole_height;
    pole_radius_ = input.pole_radius;
    design_ = input.design;
    design_file_ = input.design_file;
  }
  grid_.cols = input.cols;
  grid_.rows = input.rows;
  grid_.x = input.x;
  grid_.y = input.y;
  grid_.z = input.z;
  const bool wireframe = input.shading == render::ShadingMode::kWireframe;
  const int factor = wireframe ? 1 : render::RefinementFor(grid_, input.camera);
  render::RefineGrid(grid_, factor, float(input.pole_radius), &surface_);
  render::UpdateFlagMesh(surface_.cols, surface_.rows, surface_.x.data(), surface_.y.data(),
                         surface_.z.data(), &scene_.meshes[0]);
  render::RenderOptions options;
  options.mode = input.shading;
  options.threads = threads;
  options.antialiasing = input.antialias;
  renderer_.Render(scene_, input.camera, options, &framebuffer_);
  return framebuffer_;
}

}  // namespace flagsim
