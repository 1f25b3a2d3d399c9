#include "client/video_output.hpp"

#include <cstdio>

#include "client/image_fit.hpp"

namespace flagsim {

VideoOutput::VideoOutput(std::string path, VideoFormat format, double frame_rate)
    : path_(std::move(path)), format_(format), frame_rate_(frame_rate) {}

std::vector<std::string> VideoOutput::Arguments(VideoFormat format, const std::string& path, int width,
                                                int height, double frame_rate) {
  char size[32], rate[32];
  std::snprintf(size, sizeof(size), "%dx%d", width, height);
  std::snprintf(rate, sizeof(rate), "%.6g", frame_rate);
  std::vector<std::string> arguments = {"-hide_banner", "-loglevel", "error", "-nostats", "-y",
                                        // input: raw frames on stdin
                                        "-f", "rawvideo", "-pixel_format", "rgb24", "-video_size", size,
                                        "-framerate", rate, "-i", "pipe:0"};
  const std::vector<std::string> encoding =
      format == VideoFormat::kMp4
          ? std::vector<std::string>{"-vf",       "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                     "-c:v",      "libx264",
                                     "-pix_fmt",  "yuv420p",
                                     "-movflags", "+faststart",
                                     "-f",        "mp4"}
          : std::vector<std::string>{
                "-vf",   "split[a][b];[a]palettegen=stats_mode=single[p];[b][p]paletteuse=new=1",
                "-loop", "0",
                "-f",    "gif"};
  arguments.insert(arguments.end(), encoding.begin(), encoding.end());
  arguments.push_back("file:" + path);  // "file:": a name never reads as an option or a protocol
  return arguments;
}

std::string VideoOutput::Write(const uint8_t* rgb, int width, int height) {
  if (frames_ == 0) {
    width_ = width;
    height_ = height;
    const std::string problem =
        ffmpeg_.Start("ffmpeg", Arguments(format_, path_, width, height, frame_rate_));
    if (!problem.empty()) {
      return problem + "; Debian's ffmpeg package provides it (scripts/install-deps.sh installs it)";
    }
  }
  std::vector<uint8_t> fitted;
  if (width != width_ || height != height_) {  // a video keeps one size: the first frame's
    fitted = FitImage(rgb, width, height, width_, height_);
    rgb = fitted.data();
    ++fitted_;
  }
  const std::string problem = ffmpeg_.Write(rgb, size_t(width_) * height_ * 3);
  if (!problem.empty()) return problem + " (" + ffmpeg_.Finish() + ") writing " + path_;
  ++frames_;
  return "";
}

std::string VideoOutput::Finish() {
  if (!ffmpeg_.running()) return "";
  const std::string problem = ffmpeg_.Finish();
  return problem.empty() ? "" : problem + " writing " + path_;
}

}  // namespace flagsim
