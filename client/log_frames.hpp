// The pictures in an event log: one server's TILE and FRAME events (by its channel prefix)
// fed through a TileAssembler in the log's order, as a client would have seen them live, and
// turned into a sequence of whole images that keeps the log's timing:
//
//   before the first whole frame     skipped: a log recorded mid-stream has the whole picture
//                                    once the rolling refresh has come round (within a second)
//                                    or at a keyframe; the sequence starts at the first FRAME
//                                    whose frame hash checks out
//   a FRAME whose hash checks out    its image
//   a FRAME whose hash does not      (tiles lost on the way to the recorder) the last whole
//                                    image again, so the timing holds
//   a gap in sim_time                (the server skipped frames) the last image again for each
//                                    frame time missed
//   a FRAME between two frame times  (an extra keyframe asked for by REFRESH) dropped
//   sim_time back, or far ahead      (a new session in the same log) counted afresh from there
//
// Frame times are counted from the first image at the log's frame rate (LogSurvey): image k
// belongs at sim_time first + k / frame_rate.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "client/tile_assembler.hpp"
#include "messages/channels.hpp"
#include "messages/event_log_reader.hpp"

namespace flagsim {

/// Hz of simulated time: the fastest frame rate a log is believed to have, the most the server
/// draws (its frame_rate parameter's largest). A damaged log's PARAMS or FRAME times may claim
/// more, and keeping the timing would then repeat a frame billions of times.
constexpr double kMaxFrameRate = 120;

/// What a first pass over a log finds, reading only its FRAME and PARAMS events.
struct LogSurvey {
  int64_t manifests = 0;          ///< FRAME events with the prefix
  int64_t keyframes = 0;          ///< of them, keyframes
  int width = 0, height = 0;      ///< px, of the first frame
  double frame_rate = 0;          ///< Hz of simulated time, up to kMaxFrameRate; 0 if the log does not tell
  std::string frame_rate_source;  ///< "PARAMS" or "FRAME times", for the user
  std::string problem;            ///< how the log ended if not cleanly (EventLogReader::problem)
};

/// Surveys the log at `path` (throws std::runtime_error if it cannot be read).
LogSurvey SurveyLog(const std::string& path, const Channels& channels);

/// The frame rate of manifests at `sim_times` (s, in order): one over the mean of the intervals
/// near the median one (gaps and extra frames left out); 0 with fewer than two.
double EstimateFrameRate(const std::vector<double>& sim_times);

/// Counts of what the export met, for the user.
struct LogFramesReport {
  int64_t skipped_before_whole = 0;  ///< FRAMEs before the first whole frame
  int64_t lost = 0;                  ///< FRAMEs whose hash did not check out: repeated
  int64_t gaps = 0;                  ///< frame times with no FRAME: repeated
  int64_t dropped = 0;               ///< FRAMEs between two frame times
  int64_t time_jumps = 0;            ///< sim_time going back or far ahead: counted afresh
  int64_t undecodable = 0;           ///< TILE or FRAME events that are not one
  int64_t refused_tiles = 0;         ///< tiles the assembler refused (bad data)
};

class LogFrames {
 public:
  static constexpr double kMaxGapSeconds = 60;  ///< of simulated time: a longer jump starts afresh

  /// Reads the log at `path` (throws std::runtime_error if it cannot); `frame_rate` Hz of
  /// simulated time sets the frame times (0: no gaps filled, no frames dropped).
  LogFrames(const std::string& path, const Channels& channels, double frame_rate);

  /// The next image, RGB8 rows top to bottom, valid until the next call; false once the log is
  /// done (then reader() says how it ended).
  bool Next();
  const std::vector<uint8_t>& image() const { return image_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int64_t frame_id() const { return frame_id_; }  ///< the FRAME it shows
  bool repeated() const { return repeated_; }     ///< a repeat of the image before

  int64_t images() const { return images_; }  ///< returned so far
  const LogFramesReport& report() const { return report_; }
  const EventLogReader& reader() const { return reader_; }

 private:
  /// Reads events up to the next FRAME that places an image (or to the end); false at the end.
  bool ReadToNextFrame();
  void OnTile(const std::vector<uint8_t>& data);
  /// Decides what a manifest adds to the sequence; true if it adds something.
  bool OnManifest(const std::vector<uint8_t>& data);
  /// The place in the sequence of a FRAME at `sim_time`, counted from the first image.
  int64_t FrameSlot(double sim_time);

  EventLogReader reader_;
  Channels channels_;
  double frame_rate_;
  TileAssembler assembler_;
  LogEvent event_;
  bool started_ = false;     ///< the first whole image has come
  double last_time_ = 0;     ///< s, simulated: the last FRAME's
  double first_time_ = 0;    ///< s, simulated: the first image's
  int64_t repeats_due_ = 0;  ///< images to repeat before the next new one
  bool new_image_due_ = false;
  std::vector<uint8_t> next_image_;  ///< the new image, waiting behind the repeats
  int next_width_ = 0, next_height_ = 0;
  int64_t next_frame_id_ = -1;
  std::vector<uint8_t> image_;  ///< the image returned last
  int width_ = 0, height_ = 0;
  int64_t frame_id_ = -1;
  bool repeated_ = false;
  int64_t images_ = 0;
  LogFramesReport report_;
};

}  // namespace flagsim
