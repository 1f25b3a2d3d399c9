#include "client/frame_output.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "common/png_file.hpp"
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

/// "" if `directory`, where `path` goes, is a directory we may write in; else what stands in the way.
std::string CheckDirectoryToWriteIn(const std::string& path, const std::filesystem::path& directory) {
  std::error_code error;
  if (!std::filesystem::is_directory(directory, error))
    return "cannot write " + path + ": there is no directory " + directory.string();
  if (access(directory.c_str(), W_OK) != 0)
    return "cannot write " + path + ": " + directory.string() + ": " + std::strerror(errno);
  return "";
}

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

std::string CheckOutputFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::is_directory(path, error)) return "cannot write " + path + ": it is a directory";
  const fs::path directory = fs::path(path).parent_path();
  const std::string problem = CheckDirectoryToWriteIn(path, directory.empty() ? fs::path(".") : directory);
  if (!problem.empty()) return problem;
  if (fs::exists(path, error) && access(path.c_str(), W_OK) != 0)
    return "cannot write " + path + ": " + std::strerror(errno);
  return "";
}

// A video: a file. A PNG directory is made when written: the nearest directory that exists
// must take it.
std::string CheckOutputPath(OutputKind kind, const std::string& path) {
  if (kind != OutputKind::kPngDirectory) return CheckOutputFile(path);
  namespace fs = std::filesystem;
  std::error_code error;
  fs::path directory = path;
  while (!fs::exists(directory, error)) {
    const fs::path parent = directory.parent_path();
    directory = parent.empty() ? fs::path(".") : parent;
  }
  return CheckDirectoryToWriteIn(path, directory);
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
