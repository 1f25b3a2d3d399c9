#include "server/render_command.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <system_error>

#include "client/png_file.hpp"
#include "client/progress_bar.hpp"
#include "messages/channels.hpp"
#include "messages/utime.hpp"
#include "server/service/log_publisher.hpp"
#include "server/service/offline_render.hpp"

namespace flagsim {
namespace {

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

}  // namespace

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

}  // namespace flagsim
