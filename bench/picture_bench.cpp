// How close the live picture is to the right one, and what it costs: the default scene (the
// breeze) stepped to a few times, each frame drawn as the server draws it (FramePainter: the
// smooth surface, the filtered pattern) at 1280 x 720 with each anti-aliasing mode, against the
// same state through the same pipeline at 3x the width and height with 8 samples a pixel, each
// 3 x 3 block averaged (the supersampled picture a person would call right: 72 samples a
// pixel), and against the same at 4x (128 samples a pixel).
//
//   build/bench/picture_bench [--frames N] [--out DIR]
//
// --out DIR writes, per time, the frame with the default anti-aliasing, the 3x reference and
// their difference (times 4) as PNGs, to look at where the error is.
// Per time and mode: PSNR (RGB, peak 255) over the region around the flag and the pole (the box
// of their projected points, 8 px more on each side) against each reference and over the whole
// image against the first, and the median time to paint one frame on one and on two threads
// (N paints, 3 first discarded; default 20).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "bench/measure.hpp"
#include "common/png_file.hpp"
#include "server/scene/scene.hpp"
#include "server/service/frame_painter.hpp"
#include "server/service/session.hpp"

namespace flagsim {
namespace {

constexpr int kFactors[] = {3, 4};              ///< the references' pixels per pixel along each axis
constexpr double kTimes[] = {0.25, 0.5, 0.75};  ///< s of simulated time
constexpr int kMargin = 8;                      ///< px around the flag and pole's box

/// 1 inside the box of the flag's nodes and the pole's ends as `input`'s camera sees them, widened
/// by kMargin, per pixel.
std::vector<uint8_t> FlagRegion(const FrameInput& input) {
  const render::Camera& camera = input.camera;
  const Eigen::Matrix4d clip_from_world = camera.Projection() * camera.View();
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  const auto add = [&](double x, double y, double z) {
    Eigen::Vector2d pixel;
    if (!render::ToPixel(clip_from_world, camera, x, y, z, &pixel)) return;
    x0 = std::min(x0, pixel.x()), y0 = std::min(y0, pixel.y());
    x1 = std::max(x1, pixel.x()), y1 = std::max(y1, pixel.y());
  };
  for (size_t i = 0; i < input.x.size(); ++i) add(input.x[i], input.y[i], input.z[i]);
  add(0, 0, 0);
  add(0, input.pole_height + 0.1, 0);
  std::vector<uint8_t> mask(size_t(camera.width) * camera.height, 0);
  for (int y = std::max(0, int(y0) - kMargin); y < std::min(camera.height, int(y1) + kMargin); ++y) {
    for (int x = std::max(0, int(x0) - kMargin); x < std::min(camera.width, int(x1) + kMargin); ++x)
      mask[size_t(y) * camera.width + x] = 1;
  }
  return mask;
}

/// DIR/frame_T.png, reference_T.png and difference_T.png (|frame - reference| times 4, per channel).
void WriteComparison(const std::string& dir, double time, const render::Framebuffer& frame,
                     const std::vector<uint8_t>& reference) {
  std::filesystem::create_directories(dir);
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, "_%.2f.png", time);
  std::vector<uint8_t> difference(frame.rgb.size());
  for (size_t i = 0; i < difference.size(); ++i)
    difference[i] = uint8_t(std::min(255, 4 * std::abs(int(frame.rgb[i]) - int(reference[i]))));
  for (const auto& [name, rgb] :
       {std::pair{"frame", frame.rgb.data()}, std::pair{"reference", reference.data()},
        std::pair{"difference", static_cast<const uint8_t*>(difference.data())}}) {
    const std::string problem = WritePng(dir + "/" + name + suffix, frame.width, frame.height, rgb);
    if (!problem.empty()) std::fprintf(stderr, "picture_bench: %s\n", problem.c_str());
  }
}

}  // namespace
}  // namespace flagsim

int main(int argc, char** argv) {
  using namespace flagsim;
  int frames = 20;
  std::string out_dir;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--frames") == 0) frames = std::max(1, std::atoi(argv[i + 1]));
    if (std::strcmp(argv[i], "--out") == 0) out_dir = argv[i + 1];
  }
  const Scene scene;  // the breeze: the default scene, at its default camera (1280 x 720)
  Session session(scene);
  std::printf("%-6s %-6s %10s %10s %10s %9s %9s %8s\n", "t (s)", "aa", "flag dB 3x", "flag dB 4x", "image dB",
              "1 thr ms", "2 thr ms", "grid");
  for (const double time : kTimes) {
    while (session.simulation().state().time < time - 1e-9) session.Step();
    FrameInput input = FrameInput::Of(session, 0);
    std::vector<std::vector<uint8_t>> references;
    for (const int factor : kFactors) {
      FrameInput large = input;
      large.camera.width *= factor;
      large.camera.height *= factor;
      large.antialias = render::Antialiasing::kMsaa8;
      FramePainter reference_painter;
      const render::Framebuffer& supersampled = reference_painter.Paint(large, 2);
      references.push_back(bench::BoxFilter(supersampled.rgb, supersampled.width, factor));
    }
    const std::vector<uint8_t> region = FlagRegion(input);
    for (size_t mode = 0; mode < render::AntialiasingNames().size(); ++mode) {
      input.antialias = render::Antialiasing(mode);
      FramePainter painter;
      const render::Framebuffer frame = painter.Paint(input, 2);
      if (!out_dir.empty() && input.antialias == ServiceSettings{}.antialias) {
        WriteComparison(out_dir, time, frame, references[0]);
      }
      const double one = bench::MedianMs(3, frames, [&] { painter.Paint(input, 1); });
      const double two = bench::MedianMs(3, frames, [&] { painter.Paint(input, 2); });
      std::printf("%-6.2f %-6s %10.2f %10.2f %10.2f %9.2f %9.2f %5dx%d\n", time,
                  render::AntialiasingNames()[mode].c_str(), bench::Psnr(frame.rgb, references[0], &region),
                  bench::Psnr(frame.rgb, references[1], &region), bench::Psnr(frame.rgb, references[0]), one,
                  two, input.cols, input.rows);
    }
  }
  return 0;
}
