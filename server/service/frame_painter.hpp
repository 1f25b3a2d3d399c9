// A frame of the session, in two halves so that drawing can run beside the stepping:
//
//   FrameInput::Of(session)   at a step boundary, on the loop's thread: copies what the picture
//                             needs (the flag's node positions, the camera, the shading, the pole,
//                             what the manifest says); the session steps on at once
//   FramePainter::Paint       anywhere later: the flag's mesh from the copy (the smooth surface
//                             through its nodes, refined for the picture: smooth_surface.hpp), drawn
//
// The painter owns the render scene (pole, ground, lights) and the renderer's buffers, so nothing
// that only steps or replays a session (flagd replay, the lab) builds them.
#pragma once

#include <vector>

#include "server/render/camera.hpp"
#include "server/render/framebuffer.hpp"
#include "server/render/renderer.hpp"
#include "server/render/shading_mode.hpp"
#include "server/render/smooth_surface.hpp"
#include "server/service/session.hpp"
#include "server/service/tile_stream.hpp"

namespace flagsim {

/// Everything a frame shows, copied from a session at one step boundary.
struct FrameInput {
  int cols = 0, rows = 0;      ///< the flag's grid
  std::vector<float> x, y, z;  ///< m, node positions, cols * rows each
  render::Camera camera;
  render::ShadingMode shading = render::ShadingMode::kGouraud;
  render::FlagDesign design = render::FlagDesign::kNordicCross;
  DesignFilePtr design_file;  ///< design kImage: the image
  render::Antialiasing antialias = render::Antialiasing::kOff;
  double pole_height = 0;  ///< m
  double pole_radius = 0;  ///< m
  FrameInfo info;          ///< for the manifest: the step, the time, the camera

  /// The session as it stands, with the manifest's wall-clock stamp `utime` (µs since the epoch).
  static FrameInput Of(const Session& session, int64_t utime);
};

class FramePainter {
 public:
  /// Draws `input` on `threads` threads; the image stays valid until the next Paint.
  const render::Framebuffer& Paint(const FrameInput& input, int threads);
  const render::Framebuffer& frame() const { return framebuffer_; }

 private:
  render::NodeGrid grid_;     ///< the simulated nodes
  render::NodeGrid surface_;  ///< the smooth surface through them, refined for the picture
  render::RenderScene scene_;
  double pole_height_ = -1, pole_radius_ = -1;                    ///< m, what scene_ was built for
  render::FlagDesign design_ = render::FlagDesign::kNordicCross;  ///< what scene_'s pattern shows
  DesignFilePtr design_file_;                                     ///< the same
  render::Renderer renderer_;
  render::Framebuffer framebuffer_;
};

}  // namespace flagsim
