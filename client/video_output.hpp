// Frames into a video file through an ffmpeg child process: raw RGB8 frames go down a pipe,
// ffmpeg encodes them.
//
//   mp4   H.264 by libx264, yuv420p (what players expect), an odd width or height padded to
//         even with one black column or row (yuv420p needs even sizes)
//   gif   each frame with a palette of its own (palettegen and paletteuse, frame by frame, so
//         memory stays one frame whatever the length), looping
//
// A video has one size, the first frame's: a later frame of another size is scaled to fit it,
// keeping its shape, centred on black (image_fit.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "client/child_process.hpp"
#include "client/frame_output.hpp"

namespace flagsim {

enum class VideoFormat { kMp4, kGif };

class VideoOutput final : public FrameOutput {
 public:
  VideoOutput(std::string path, VideoFormat format, double frame_rate);

  /// The first frame starts ffmpeg; a frame of another size is fitted to the first's. Returns ""
  /// or what went wrong: ffmpeg missing or failed.
  std::string Write(const uint8_t* rgb, int width, int height) override;
  std::string Finish() override;
  int64_t frames() const override { return frames_; }
  int64_t fitted() const override { return fitted_; }

  /// ffmpeg's arguments for `width` x `height` frames at `frame_rate` Hz into `path`.
  static std::vector<std::string> Arguments(VideoFormat format, const std::string& path, int width,
                                            int height, double frame_rate);

 private:
  std::string path_;
  VideoFormat format_;
  double frame_rate_;
  ChildProcess ffmpeg_;
  int width_ = 0, height_ = 0;
  int64_t frames_ = 0;
  int64_t fitted_ = 0;  ///< frames of another size than the first, scaled to fit it
};

}  // namespace flagsim
