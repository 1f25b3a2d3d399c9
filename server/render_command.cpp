// flagd render: a scene offline, no network, as fast as the machine goes (service/offline_render.hpp),
// into an LCM log (the channels a live server publishes, stamped in simulated time) and/or PNG
// frames; the command line's side: its options, the files, the progress bar and the summary.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <system_error>

#include "common/cli_checks.hpp"
#include "common/png_file.hpp"
#include "common/progress_bar.hpp"
#include "messages/channels.hpp"
#include "messages/utime.hpp"
#include "server/flagd_commands.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/scene/scene_file.hpp"
#include "server/service/log_publisher.hpp"
#include "server/service/offline_render.hpp"

namespace flagsim {
namespace {

struct RenderRequest {
  std::string log_path;  ///< the LCM log to write; "" for none
  std::string png_dir;   ///< where frame_%06d.png go; "" for none
  double duration = 0;   ///< s of simulated time
  std::string prefix;    ///< of the logged channels
  double fps = std::nan("");  ///< Hz; NaN: the scene's frame_rate
  int threads = 0;            ///< 0: the scene's threads
};

/// The frame sink that writes each frame as DIR/frame_%06d.png (nothing without a directory).
OfflineRender::FrameSink PngWriter(const std::string& directory) {
  if (directory.empty()) return nullptr;
  return [directory](int64_t frame_id, const render::Framebuffer& image) {
    const std::string problem =
        WritePng(PngFramePath(directory, frame_id), image.width, image.height, image.rgb.data());
    if (!problem.empty()) throw std::runtime_error(problem);
  };
}

std::string Summary(const RenderRequest& request, const OfflineRender& render, const LogPublisher* log,
                    double wall_seconds) {
  const OfflineRenderStats& stats = render.stats();
  const double simulated = render.session().simulation().state().time;
  char line[512];
  std::snprintf(line, sizeof(line),
                "rendered %.3f s of simulated time in %.2f s (%.1f x real time): %lld frames", simulated,
                wall_seconds, wall_seconds > 0 ? simulated / wall_seconds : 0.0,
                static_cast<long long>(stats.frames));
  std::string summary = line;
  if (log != nullptr) {
    std::snprintf(
        line, sizeof(line),
        "\n%s: %lld events (%lld STATE, %lld PARAMS, %lld TILE, %lld FRAME of which %lld keyframes), %.1f KB",
        log->path().c_str(), static_cast<long long>(log->events()), static_cast<long long>(stats.states),
        static_cast<long long>(stats.params), static_cast<long long>(stats.tiles),
        static_cast<long long>(stats.frames), static_cast<long long>(stats.keyframes), log->bytes() / 1024.0);
    summary += line;
  }
  if (!request.png_dir.empty()) {
    summary +=
        "\n" + request.png_dir + ": " + std::to_string(stats.frames) + " PNG frames (frame_000000.png ...)";
  }
  return summary;
}

/// --fps and --threads are parameters, checked by the table after the --set ones. Throws
/// SceneError naming the option.
void ApplyRenderOverrides(const RenderRequest& request, Scene* scene) {
  const auto assign = [scene](const char* option, const char* name, double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.17g", value);
    const std::string problem = ParameterTable::Get().Assign(name, text, scene);
    if (!problem.empty()) throw SceneError(std::string(option) + " " + problem);
  };
  if (!std::isnan(request.fps)) {
    // frame_rate 0 is a live server's "no frames"; a render's frames are what it is for.
    const Parameter& rate = *ParameterTable::Get().Find("frame_rate");
    if (!(request.fps > 0) || request.fps > rate.max_value) {
      throw SceneError("--fps: " + rate.Format(request.fps) + " is out of range; a render draws frames, so allowed above 0 .. " +
                       rate.Format(rate.max_value) + " " + rate.unit);
    }
    assign("--fps", "frame_rate", request.fps);
  }
  if (request.threads > 0) assign("--threads", "threads", request.threads);
}

/// A render writes something and draws frames. Throws SceneError (a usage error) if not.
void CheckRender(const RenderRequest& request, const Scene& scene) {
  if (request.log_path.empty() && request.png_dir.empty()) {
    throw SceneError("render: nothing to write; give -o LOG, --png-dir DIR or both");
  }
  if (scene.service.frame_rate <= 0) {
    throw SceneError("render: frame_rate is 0 in the scene, so no frame would be drawn; give --fps F");
  }
}

// log file, PNG directory => OfflineRender, frame by frame, with progress => summary
int RunRender(const Scene& scene, const RenderRequest& request, const std::atomic<bool>& stop) {
  const Channels channels(request.prefix);
  const double start = MonotonicSeconds();
  ProgressBar bar;
  try {
    std::unique_ptr<LogPublisher> log;
    if (!request.log_path.empty()) log = std::make_unique<LogPublisher>(request.log_path, UnixMicros());
    if (!request.png_dir.empty()) {
      std::error_code error;
      std::filesystem::create_directories(request.png_dir, error);
      if (error)
        throw std::runtime_error("cannot make the directory " + request.png_dir + ": " + error.message());
    }
    OfflineRender render(scene, request.duration, channels, log.get(), PngWriter(request.png_dir));
    while (!stop.load() && render.Advance()) {
      char detail[96];
      std::snprintf(detail, sizeof(detail), "frame %lld  t %.2f / %.2f s",
                    static_cast<long long>(render.stats().frames), render.session().simulation().state().time,
                    request.duration);
      bar.Update(render.progress(), detail);
    }
    if (log) log->Close();
    bar.Finish(Summary(request, render, log.get(), MonotonicSeconds() - start));
    if (!render.done()) {
      std::fprintf(stderr, "flagd: interrupted at t = %.3f s; what was written so far is whole\n",
                   render.session().simulation().state().time);
      return 1;
    }
  } catch (const std::exception& error) {
    bar.Finish(std::string("flagd: ") + error.what());
    return 1;
  }
  return 0;
}

}  // namespace

void AddRenderCommand(CLI::App& app, FlagdInvocation& invocation) {
  auto request = std::make_shared<RenderRequest>();
  CLI::App* render = app.add_subcommand(
      "render",
      "run a scene as fast as possible with no network, into an LCM log (the channels a live server "
      "publishes, stamped in simulated time: lcm-logplayer plays it in real time) and/or PNG frames");
  render->add_option("--duration", request->duration, "seconds of simulated time to render")
      ->required()
      ->check(AboveZero());
  render->add_option("--fps", request->fps,
                     "frames per second of simulated time, above 0 (default: the scene's frame_rate, 30)");
  render->add_option("-o,--output", request->log_path, "the LCM log to write");
  render->add_option("--png-dir", request->png_dir, "also write each frame there as frame_%06d.png");
  render->add_option("--threads", request->threads, "worker threads (default: the scene's threads)")->check(AboveZero());
  render->footer("--scene, --set and --prefix (the logged channels') are taken as for the server.");
  invocation.RunOnParse(render, [&invocation, request] {
    if (invocation.StartsAServer()) return int(kFlagdUsage);
    Scene scene;
    try {
      scene = BuildScene(invocation.globals);
      ApplyRenderOverrides(*request, &scene);
      CheckRender(*request, scene);
    } catch (const SceneError& error) {
      std::fprintf(stderr, "flagd: %s\n", error.what());
      return int(kFlagdUsage);
    }
    request->prefix = invocation.globals.prefix;
    return RunRender(scene, *request, invocation.stop);
  });
}

}  // namespace flagsim
