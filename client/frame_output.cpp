#include "client/frame_output.hpp"

#include <filesystem>
#include <system_error>

#include "client/png_file.hpp"
#include "client/video_output.hpp"

namespace flagsim {
namespace {

bool EndsWith(const std::string& text, const std::string& end) {
  return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

/// A numbered PNG per frame, in a directory made when the first frame comes.
class PngDirectory final : public FrameOutput {
 public:
  explicit PngDirectory(std::string directory) : directory_(std::move(directory)) {}

  std::string Write(const uint8_t* rgb, int width, int height) override {
    if (frames_ == 0) {
      std::error_code error;
      std::filesystem::create_directories(directory_, error);
      if (error) return "cannot make the directory " + directory_ + ": " + error.message();
    }
    const std::string problem = WritePng(PngFramePath(directory_, frames_), width, height, rgb);
    if (problem.empty()) ++frames_;
    return problem;
  }
  std::string Finish() override { return ""; }
  int64_t frames() const override { return frames_; }

 private:
  std::string directory_;
  int64_t frames_ = 0;
};

}  // namespace

std::optional<OutputKind> OutputKindOf(const std::string& path, std::string* error) {
  std::error_code ignored;
  if (EndsWith(path, "/") || std::filesystem::is_directory(path, ignored)) return OutputKind::kPngDirectory;
  if (EndsWith(path, ".mp4")) return OutputKind::kMp4;
  if (EndsWith(path, ".gif")) return OutputKind::kGif;
  *error = "cannot tell what to write from '" + path +
           "'; allowed: a directory (ending in / or existing) for PNG frames, NAME.mp4 or NAME.gif";
  return std::nullopt;
}

std::unique_ptr<FrameOutput> MakeFrameOutput(OutputKind kind, const std::string& path, double frame_rate) {
  switch (kind) {
    case OutputKind::kPngDirectory:
      return std::make_unique<PngDirectory>(path);
    case OutputKind::kMp4:
      return std::make_unique<VideoOutput>(path, VideoFormat::kMp4, frame_rate);
    case OutputKind::kGif:
      return std::make_unique<VideoOutput>(path, VideoFormat::kGif, frame_rate);
  }
  return nullptr;
}

}  // namespace flagsim
