// Where exported frames go, chosen by the output's name:
//
//   DIR/ or an existing directory   PNG files frame_000000.png, frame_000001.png, ...
//   NAME.mp4                        H.264 (libx264, yuv420p; odd sizes padded to even) by ffmpeg
//   NAME.gif                        a GIF by ffmpeg, each frame with its own palette
//
// A video keeps the first frame's size: later frames of another size are scaled to fit it,
// keeping their shape, on black. PNG frames keep each its own size.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace flagsim {

enum class OutputKind { kPngDirectory, kMp4, kGif };

/// The kind of output `path` names; nullopt with *error naming what is allowed if none.
std::optional<OutputKind> OutputKindOf(const std::string& path, std::string* error);

/// "" if an output of `kind` can be made at `path` (its directory, or the nearest that exists,
/// is a directory we may write in), else what stands in the way: checked before any work.
std::string CheckOutputPath(OutputKind kind, const std::string& path);

/// "" if a file can be written at `path` (flagctl snapshot's picture, a video): not a directory,
/// in a directory that is there and that we may write in, and if it exists, one we may write;
/// else what stands in the way, with the system's reason.
std::string CheckOutputFile(const std::string& path);

class FrameOutput {
 public:
  virtual ~FrameOutput() = default;
  /// Adds one image, RGB8 rows top to bottom. Returns "" or what went wrong (then stop).
  virtual std::string Write(const uint8_t* rgb, int width, int height) = 0;
  /// Completes the output (a video's encoder finishes); "" or what went wrong.
  virtual std::string Finish() = 0;
  virtual int64_t frames() const = 0;  ///< images written
  /// Of them, images of another size than the first, scaled to fit it (a video has one size).
  virtual int64_t fitted() const { return 0; }
};

/// An output of `kind` at `path`; a video plays at `frame_rate` Hz. Nothing is created on disk
/// until the first Write.
std::unique_ptr<FrameOutput> MakeFrameOutput(OutputKind kind, const std::string& path, double frame_rate);

}  // namespace flagsim
