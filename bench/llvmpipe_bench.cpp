// Flagsim's renderer (Gouraud) against Mesa's llvmpipe drawing the same scene with OpenGL's fixed
// function (gl_scene.hpp), in the same run and at equal quality: image sizes x flag grids x
// threads x anti-aliasing (none, or 4 samples a pixel on both sides; the pattern trilinear on
// both), the median time to a finished image in memory, and the PSNR between the two images.
//
//   build/bench/llvmpipe_bench [--threads N] [--frames N] [--out DIR]
//
// --threads N   only N threads (default: 1 and 2)
// --frames N    timed frames per renderer and configuration (default 30; 5 more are discarded)
// --out DIR     write both images of 1280x720 with the 64x48 flag as PNGs into DIR
//
// What one frame's time covers:
//   flagsim    Renderer::Render: the RGB8 image is in its Framebuffer when it returns
//   llvmpipe   the draw calls (the vertex arrays sent again), glFinish and glReadPixels into
//              RGBA8 memory; the flip to RGB8 rows top first, for the comparison, is not timed
//
// llvmpipe takes its thread count from LP_NUM_THREADS when EGL initialises, once per process,
// so each thread count runs in a child process that sets it first; flagsim gets the same count
// through RenderOptions::threads. (LP_NUM_THREADS counts llvmpipe's rasterising threads; the
// calling thread transforms and bins a frame's triangles before they start on it.)
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "bench/flag_pose.hpp"
#include "bench/gl_scene.hpp"
#include "bench/measure.hpp"
#include "common/png_file.hpp"
#include "server/render/renderer.hpp"

namespace flagsim {
namespace {

constexpr int kWarmupFrames = 5;  ///< drawn and discarded before timing
constexpr std::pair<int, int> kImageSizes[] = {{640, 480}, {1280, 720}, {1920, 1080}};  ///< px
constexpr std::pair<int, int> kFlagGrids[] = {{32, 24}, {64, 48}, {128, 96}};           ///< nodes
constexpr std::pair<int, int> kSavedSize{1280, 720}, kSavedGrid{64, 48};  ///< the pair --out writes
constexpr int kSampleCounts[] = {1, 4};  ///< per pixel: no anti-aliasing, then 4x multisampling

struct Options {
  std::vector<int> threads{1, 2};
  int frames = 30;
  std::string out_dir;  ///< "" writes nothing
};

/// One line of the table.
struct Row {
  int width = 0, height = 0, cols = 0, rows = 0, threads = 0, samples = 1;
  double flagsim_ms = 0;   ///< median per frame
  double llvmpipe_ms = 0;  ///< median per frame
  double psnr_db = 0;      ///< infinite when the images are equal
};

/// Two RGB8 images of one size, each row top first.
struct ImagePair {
  std::vector<uint8_t> flagsim, llvmpipe;
};

bool ParseOptions(int argc, char** argv, Options* options) {
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) return false;
    const std::string value = argv[++i];
    if (flag == "--threads") {
      options->threads = {std::atoi(value.c_str())};
      if (options->threads[0] < 1) return false;
    } else if (flag == "--frames") {
      options->frames = std::atoi(value.c_str());
      if (options->frames < 1) return false;
    } else if (flag == "--out") {
      options->out_dir = value;
    } else {
      return false;
    }
  }
  return true;
}

/// (scene, camera, threads, samples: 1 or 4) => flagsim's median frame time, and its last image.
double TimeFlagsim(const render::RenderScene& scene, const render::Camera& camera, int threads, int samples,
                   int frames, std::vector<uint8_t>* image) {
  render::RenderOptions options;
  options.mode = render::ShadingMode::kGouraud;
  options.threads = threads;
  options.antialiasing = samples > 1 ? render::Antialiasing::kMsaa4 : render::Antialiasing::kOff;
  render::Renderer renderer;
  render::Framebuffer framebuffer;
  const double ms =
      bench::MedianMs(kWarmupFrames, frames, [&] { renderer.Render(scene, camera, options, &framebuffer); });
  *image = framebuffer.rgb;
  return ms;
}

/// (scene, camera, samples) => llvmpipe's median frame time, and its last image as RGB8 rows top
/// first.
double TimeLlvmpipe(const render::RenderScene& scene, const render::Camera& camera, int samples, int frames,
                    std::vector<uint8_t>* image, std::string* error) {
  bench::GlSceneRenderer renderer;
  *error = renderer.Init(camera.width, camera.height, samples, scene.pattern);
  if (!error->empty()) return 0;
  std::vector<uint8_t> rgba;
  const double ms = bench::MedianMs(kWarmupFrames, frames, [&] { renderer.Render(scene, camera, &rgba); });
  *image = bench::RgbTopDown(rgba, camera.width, camera.height);
  return ms;
}

/// row's images => DIR/flagsim_WxH_CxR_Nt.png and DIR/llvmpipe_..., or what went wrong.
std::string WriteImages(const std::string& out_dir, const Row& row, const ImagePair& images) {
  std::error_code ignored;
  std::filesystem::create_directories(out_dir, ignored);
  const std::string suffix = std::to_string(row.width) + "x" + std::to_string(row.height) + "_" +
                             std::to_string(row.cols) + "x" + std::to_string(row.rows) + "_" +
                             std::to_string(row.threads) + "t_" + std::to_string(row.samples) + "s.png";
  std::string error = WritePng(out_dir + "/flagsim_" + suffix, row.width, row.height, images.flagsim.data());
  if (error.empty()) {
    error = WritePng(out_dir + "/llvmpipe_" + suffix, row.width, row.height, images.llvmpipe.data());
  }
  return error;
}

/// (image size, flag grid, threads) => both renderers timed and compared, images written if asked.
bool Measure(Row* row, const Options& options) {
  render::RenderScene scene = bench::BenchScene(row->cols, row->rows);
  // OpenGL's fixed function casts no shadow and knows no wrapped light or sheen: neither side
  // draws them, so that the two draw the same picture.
  scene.shadow_light = -1;
  for (render::Material& material : scene.materials) material.wrap = material.sheen = 0;
  render::Camera camera;
  camera.width = row->width;
  camera.height = row->height;
  ImagePair images;
  std::string error;
  row->flagsim_ms = TimeFlagsim(scene, camera, row->threads, row->samples, options.frames, &images.flagsim);
  row->llvmpipe_ms = TimeLlvmpipe(scene, camera, row->samples, options.frames, &images.llvmpipe, &error);
  if (error.empty()) row->psnr_db = bench::Psnr(images.flagsim, images.llvmpipe);
  const bool saved =
      std::pair{row->width, row->height} == kSavedSize && std::pair{row->cols, row->rows} == kSavedGrid;
  if (error.empty() && saved && !options.out_dir.empty()) error = WriteImages(options.out_dir, *row, images);
  if (!error.empty()) std::fprintf(stderr, "llvmpipe_bench: %s\n", error.c_str());
  return error.empty();
}

void PrintHeader() {
  std::printf("%-10s %-7s %7s %7s %11s %11s %15s %9s\n", "size", "flag", "threads", "samples", "flagsim ms",
              "llvmpipe ms", "flagsim/llvmp.", "PSNR dB");
}

void PrintRow(const Row& row) {
  const std::string size = std::to_string(row.width) + "x" + std::to_string(row.height);
  const std::string flag = std::to_string(row.cols) + "x" + std::to_string(row.rows);
  std::printf("%-10s %-7s %7d %7d %11.2f %11.2f %15.2f %9.2f\n", size.c_str(), flag.c_str(), row.threads,
              row.samples, row.flagsim_ms, row.llvmpipe_ms, row.flagsim_ms / row.llvmpipe_ms, row.psnr_db);
  std::fflush(stdout);
}

/// threads => LP_NUM_THREADS set, a GL context on llvmpipe, every size and grid measured and
/// printed; the process's exit status.
int RunThreadCount(int threads, const Options& options) {
  setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 1);
  bench::GlContext context;
  const std::string error = context.Open();
  if (!error.empty()) {
    std::fprintf(stderr, "llvmpipe_bench: %s\n", error.c_str());
    return 1;
  }
  const std::string renderer = context.RendererName();
  std::fprintf(stderr, "llvmpipe_bench: %d thread(s), GL_RENDERER %s\n", threads, renderer.c_str());
  if (renderer.find("llvmpipe") == std::string::npos) {
    std::fprintf(stderr, "llvmpipe_bench: not llvmpipe (try LIBGL_ALWAYS_SOFTWARE=1)\n");
    return 1;
  }
  for (const auto& [width, height] : kImageSizes) {
    for (const auto& [cols, rows] : kFlagGrids) {
      for (const int samples : kSampleCounts) {
        Row row{width, height, cols, rows, threads, samples};
        if (!Measure(&row, options)) return 1;
        PrintRow(row);
      }
    }
  }
  return 0;
}

/// threads => RunThreadCount in a child process (a fresh llvmpipe); its exit status.
int RunInChild(int threads, const Options& options) {
  std::fflush(nullptr);
  const pid_t child = fork();
  if (child < 0) return 1;
  if (child == 0) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);  // no orphan left measuring if the parent is stopped
    const int status = RunThreadCount(threads, options);
    std::fflush(nullptr);
    _exit(status);
  }
  int status = 0;
  if (waitpid(child, &status, 0) != child) return 1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

}  // namespace
}  // namespace flagsim

int main(int argc, char** argv) {
  flagsim::Options options;
  if (!flagsim::ParseOptions(argc, argv, &options)) {
    std::fprintf(stderr, "usage: %s [--threads N] [--frames N] [--out DIR]\n", argv[0]);
    return 2;
  }
  flagsim::PrintHeader();
  int status = 0;
  for (const int threads : options.threads) status |= flagsim::RunInChild(threads, options);
  return status;
}
