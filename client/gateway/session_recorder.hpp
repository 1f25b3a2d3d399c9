// The gateway's recorder (service /flag/record): every channel of the server into an LCM log,
// as `flagctl record` makes one, started and stopped by any client; once stopped, the log is
// served for download at /recordings/NAME, and so are the files made from it (MCAP, a video:
// recording_exports.hpp) once each is whole. One recording at a time, bounded in size.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "client/gateway/recording_exports.hpp"
#include "client/log_recorder.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"

namespace flagsim::gateway {

class SessionRecorder {
 public:
  static constexpr uint64_t kMaxBytes = uint64_t(4) << 30;  ///< a recording stops at this size

  /// Records every channel of `channels`; logs go into `directory` (made when the first
  /// recording starts), named STEM-DATE-TIME.lcmlog, and each finished one is exported in `formats`.
  SessionRecorder(Bus& bus, const Channels& channels, std::string directory,
                  std::vector<RecordingExports::Format> formats = {}, std::string stem = "flagsim");
  ~SessionRecorder();

  /// Each answers with the recording's state (schemas/record_result.json).
  nlohmann::json Start(double now);
  nlohmann::json Stop(double now);
  nlohmann::json Status(double now) const;
  /// Stops a recording that failed (a full disk) or grew past kMaxBytes; true if it did, and
  /// then last_error() says why.
  bool StopIfDone(double now);
  /// Why the last recording stopped on its own (what the disk-full log holds), or why the last
  /// request failed; "" if none.
  const std::string& last_error() const { return last_error_; }

  bool recording() const { return recorder_ != nullptr; }
  /// Whether the recording needs a keyframe request now (LogRecorder::KeyframeRequestDue).
  bool KeyframeRequestDue(double now) { return recorder_ && recorder_->KeyframeRequestDue(now); }
  /// The path of a finished recording of this recorder's (its stem), or a finished export of
  /// one, named `name` (no directories in it); nullopt if none.
  std::optional<std::string> FinishedFile(std::string_view name) const;

 private:
  nlohmann::json State(double now, const std::string& error = "") const;

  Bus& bus_;
  const Channels& channels_;
  std::string directory_;
  std::string stem_;
  std::unique_ptr<LogRecorder> recorder_;
  std::string name_;  ///< the current or last recording's file name
  double started_ = 0;
  double stopped_ = 0;
  int64_t last_events_ = 0;
  uint64_t last_bytes_ = 0;
  std::string last_error_;
  RecordingExports exports_;
};

}  // namespace flagsim::gateway
