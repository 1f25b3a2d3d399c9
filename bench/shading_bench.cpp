// Speed against accuracy of the shading modes: for each mode and flag grid at 1280x720 on two
// threads, the median time per frame and the PSNR against supersampled Phong.
//
//   build/bench/shading_bench [--csv FILE] [--frames N] [--images DIR]
//
// --csv FILE    also write the table as CSV: mode,cols,rows,ms,psnr_image_db,psnr_flag_db,
//               psnr_flag_phong_db (the flag against Phong at the same size: shading error alone)
// --frames N    timed frames per mode and grid (default 30; 5 more are drawn first and discarded)
// --images DIR  write every measured frame and each reference as binary PPM into DIR
//
// Per flag grid (bench::BenchScene):
//   reference   Phong drawn by the same Renderer at 4x the width and height (same camera
//               otherwise), each 4x4 block of samples averaged to one pixel, rounded to nearest
//   flag mask   the pixels where the flag is drawn in the 1280x720 frame: the full scene's depth
//               buffer equals that of a scene holding only the flag (so the pole in front of the
//               flag is not counted); the same for every filled mode, which share coverage
//   per mode    time: std::chrono::steady_clock around Renderer::Render only
//               PSNR: RGB, peak 255, over the whole image and over the flag mask
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "bench/flag_pose.hpp"
#include "bench/measure.hpp"
#include "server/render/renderer.hpp"
#include "server/render/shading_mode.hpp"

namespace flagsim {
namespace {

constexpr int kWarmupFrames = 5;   ///< drawn and discarded before timing
constexpr int kWidth = 1280;       ///< px, measured frames
constexpr int kHeight = 720;       ///< px
constexpr int kThreads = 2;        ///< RenderOptions::threads, for the frames and the reference
constexpr int kSupersampling = 4;  ///< reference samples per pixel along each axis
constexpr std::pair<int, int> kFlagGrids[] = {{16, 12}, {32, 24}, {64, 48}};  ///< nodes
constexpr render::ShadingMode kModes[] = {render::ShadingMode::kWireframe, render::ShadingMode::kFlat,
                                          render::ShadingMode::kGouraud, render::ShadingMode::kPhong};

struct Options {
  int frames = 30;
  std::string csv_path;    ///< "" writes no CSV
  std::string images_dir;  ///< "" writes no images
};

/// One flag grid: its scene and what its frames are compared against (kWidth x kHeight).
struct FlagCase {
  int cols = 0, rows = 0;          ///< flag grid, nodes
  render::RenderScene scene;       ///< bench::BenchScene(cols, rows)
  std::vector<uint8_t> reference;  ///< supersampled Phong, RGB8, top row first
  std::vector<uint8_t> phong;      ///< Phong at the frame's own size: the shading without the edges
  std::vector<uint8_t> flag_mask;  ///< 1 where the flag is drawn, per pixel
};

/// One line of the table.
struct Row {
  std::string mode;
  int cols = 0, rows = 0;         ///< flag grid, nodes
  double ms = 0;                  ///< median time per frame
  double psnr_image_db = 0;       ///< whole image against the reference
  double psnr_flag_db = 0;        ///< flag pixels only
  double psnr_flag_phong_db = 0;  ///< flag pixels against Phong at the same size: shading error alone
};

bool ParseOptions(int argc, char** argv, Options* options) {
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) return false;
    const std::string value = argv[++i];
    if (flag == "--csv") {
      options->csv_path = value;
    } else if (flag == "--frames") {
      options->frames = std::atoi(value.c_str());
      if (options->frames < 1) return false;
    } else if (flag == "--images") {
      options->images_dir = value;
    } else {
      return false;
    }
  }
  return true;
}

render::Camera FrameCamera(int scale) {
  render::Camera camera;
  camera.width = kWidth * scale;
  camera.height = kHeight * scale;
  return camera;
}

render::RenderOptions FrameOptions(render::ShadingMode mode, bool keep_depth) {
  render::RenderOptions options;
  options.mode = mode;
  options.threads = kThreads;
  options.keep_depth = keep_depth;
  return options;
}

/// scene => Phong at kSupersampling times the size, box-filtered to kWidth x kHeight.
std::vector<uint8_t> SupersampledPhong(const render::RenderScene& scene) {
  render::Renderer renderer;
  render::Framebuffer large;
  renderer.Render(scene, FrameCamera(kSupersampling), FrameOptions(render::ShadingMode::kPhong, false),
                  &large);
  return bench::BoxFilter(large.rgb, large.width, kSupersampling);
}

/// scene (mesh 0 the flag) => 1 per pixel where the flag is drawn: the full scene's depth equals
/// the flag's own, drawn alone (of two equal depths the renderer keeps the first drawn: the flag).
std::vector<uint8_t> FlagMask(const render::RenderScene& scene) {
  render::RenderScene flag_only = scene;
  flag_only.meshes.resize(1);
  const render::RenderOptions options = FrameOptions(render::ShadingMode::kPhong, true);
  render::Renderer renderer;
  render::Framebuffer full, flag;
  renderer.Render(scene, FrameCamera(1), options, &full);
  renderer.Render(flag_only, FrameCamera(1), options, &flag);
  std::vector<uint8_t> mask(full.depth.size());
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = flag.depth[i] < 1.0f && flag.depth[i] == full.depth[i];
  return mask;
}

/// A kWidth x kHeight RGB8 image => a binary PPM at `path`; false if it could not be written.
bool WritePpm(const std::string& path, const std::vector<uint8_t>& rgb) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return false;
  std::fprintf(file, "P6\n%d %d\n255\n", kWidth, kHeight);
  const bool written = std::fwrite(rgb.data(), 1, rgb.size(), file) == rgb.size();
  return std::fclose(file) == 0 && written;
}

std::string GridName(int cols, int rows) { return std::to_string(cols) + "x" + std::to_string(rows); }

/// (cols, rows) => the flag's scene, its reference and flag mask; the reference written to the
/// images directory if asked.
FlagCase PrepareFlag(int cols, int rows, const Options& options) {
  FlagCase flag{cols, rows, bench::BenchScene(cols, rows), {}, {}, {}};
  flag.reference = SupersampledPhong(flag.scene);
  render::Renderer renderer;
  render::Framebuffer phong;
  renderer.Render(flag.scene, FrameCamera(1), FrameOptions(render::ShadingMode::kPhong, false), &phong);
  flag.phong = phong.rgb;
  flag.flag_mask = FlagMask(flag.scene);
  if (!options.images_dir.empty()) {
    const std::string path = options.images_dir + "/reference_" + GridName(cols, rows) + ".ppm";
    if (!WritePpm(path, flag.reference))
      std::fprintf(stderr, "shading_bench: cannot write %s\n", path.c_str());
  }
  return flag;
}

/// (flag, mode) => the mode's median frame time and both PSNRs against the flag's reference; its
/// last frame written to the images directory if asked.
Row MeasureMode(const FlagCase& flag, render::ShadingMode mode, const Options& options) {
  const render::Camera camera = FrameCamera(1);
  const render::RenderOptions render_options = FrameOptions(mode, false);
  render::Renderer renderer;
  render::Framebuffer frame;
  Row row;
  row.mode = render::ShadingModeNames()[int(mode)];
  row.cols = flag.cols;
  row.rows = flag.rows;
  row.ms = bench::MedianMs(kWarmupFrames, options.frames,
                           [&] { renderer.Render(flag.scene, camera, render_options, &frame); });
  row.psnr_image_db = bench::Psnr(frame.rgb, flag.reference, nullptr);
  row.psnr_flag_db = bench::Psnr(frame.rgb, flag.reference, &flag.flag_mask);
  row.psnr_flag_phong_db = bench::Psnr(frame.rgb, flag.phong, &flag.flag_mask);
  if (!options.images_dir.empty()) {
    const std::string path =
        options.images_dir + "/" + row.mode + "_" + GridName(flag.cols, flag.rows) + ".ppm";
    if (!WritePpm(path, frame.rgb)) std::fprintf(stderr, "shading_bench: cannot write %s\n", path.c_str());
  }
  return row;
}

void PrintHeader() {
  std::printf("%-10s %-6s %9s %15s %14s %22s\n", "mode", "flag", "ms", "PSNR image dB", "PSNR flag dB",
              "PSNR flag vs Phong dB");
}

void PrintRow(const Row& row) {
  std::printf("%-10s %-6s %9.2f %15.2f %14.2f %22.2f\n", row.mode.c_str(),
              GridName(row.cols, row.rows).c_str(), row.ms, row.psnr_image_db, row.psnr_flag_db,
              row.psnr_flag_phong_db);
  std::fflush(stdout);
}

/// table => CSV at `path`, a header line and one line per row; false if it could not be written.
bool WriteCsv(const std::string& path, const std::vector<Row>& table) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (!file) return false;
  std::fprintf(file, "mode,cols,rows,ms,psnr_image_db,psnr_flag_db,psnr_flag_phong_db\n");
  for (const Row& row : table) {
    std::fprintf(file, "%s,%d,%d,%.3f,%.2f,%.2f,%.2f\n", row.mode.c_str(), row.cols, row.rows, row.ms,
                 row.psnr_image_db, row.psnr_flag_db, row.psnr_flag_phong_db);
  }
  return std::fclose(file) == 0;
}

}  // namespace
}  // namespace flagsim

int main(int argc, char** argv) {
  flagsim::Options options;
  if (!flagsim::ParseOptions(argc, argv, &options)) {
    std::fprintf(stderr, "usage: %s [--csv FILE] [--frames N] [--images DIR]\n", argv[0]);
    return 2;
  }
  if (!options.images_dir.empty()) {
    std::error_code ignored;
    std::filesystem::create_directories(options.images_dir, ignored);
  }
  std::printf("%dx%d, %d threads, reference: %dx%d supersampled Phong\n", flagsim::kWidth, flagsim::kHeight,
              flagsim::kThreads, flagsim::kSupersampling, flagsim::kSupersampling);
  flagsim::PrintHeader();
  // Every flag's reference first, then the modes one after another: the table (and the CSV) in
  // mode order, each mode's flags together.
  std::vector<flagsim::FlagCase> flags;
  for (const auto& [cols, rows] : flagsim::kFlagGrids)
    flags.push_back(flagsim::PrepareFlag(cols, rows, options));
  std::vector<flagsim::Row> table;
  for (const flagsim::render::ShadingMode mode : flagsim::kModes) {
    for (const flagsim::FlagCase& flag : flags) {
      table.push_back(flagsim::MeasureMode(flag, mode, options));
      flagsim::PrintRow(table.back());
    }
  }
  if (!options.csv_path.empty() && !flagsim::WriteCsv(options.csv_path, table)) {
    std::fprintf(stderr, "shading_bench: cannot write %s\n", options.csv_path.c_str());
    return 1;
  }
  return 0;
}
