#include "client/log_frames.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "client/stream_reader.hpp"
#include "flagsim/params_t.hpp"
#include "messages/checked_decode.hpp"

namespace flagsim {
namespace {

template <class Message>
std::optional<Message> Decode(const std::vector<uint8_t>& data) {
  std::string error;
  return wire::CheckedDecode<Message>(data.data(), data.size(), kMaxStreamMessageBytes, &error);
}

/// The frame_rate row of a PARAMS message, or nullopt.
std::optional<double> FrameRateOf(const params_t& params) {
  for (const parameter_t& row : params.parameters) {
    if (row.name == "frame_rate" && std::isfinite(row.value)) return row.value;
  }
  return std::nullopt;
}

}  // namespace

double EstimateFrameRate(const std::vector<double>& sim_times) {
  std::vector<double> intervals;
  for (size_t i = 1; i < sim_times.size(); ++i) {
    const double interval = sim_times[i] - sim_times[i - 1];
    if (std::isfinite(interval) && interval > 0) intervals.push_back(interval);
  }
  if (intervals.empty()) return 0;
  std::vector<double> sorted = intervals;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  // Frames fall on step boundaries (intervals of 16 and 17 steps at 30 Hz): the mean of the
  // usual ones, not the median, is the rate.
  double sum = 0;
  int count = 0;
  for (const double interval : intervals) {
    if (interval < 0.5 * median || interval > 1.5 * median) continue;
    sum += interval;
    ++count;
  }
  return count / sum;
}

// FRAME and PARAMS events => counts, the first frame's size, the frame rate
LogSurvey SurveyLog(const std::string& path, const Channels& channels) {
  EventLogReader reader(path);
  LogSurvey survey;
  std::vector<double> sim_times;  // of the FRAMEs
  std::optional<double> params_rate;
  LogEvent event;
  const auto wanted = [&](const std::string& channel) {
    return channel == channels.frame || channel == channels.params;
  };
  while (reader.Next(&event, wanted)) {
    if (event.channel == channels.params) {
      const auto params = Decode<params_t>(event.data);
      // the rate in force at the first frame: the last before it, else the first after
      if (params && FrameRateOf(*params) && (survey.manifests == 0 || !params_rate)) {
        params_rate = FrameRateOf(*params);
      }
      continue;
    }
    const auto manifest = Decode<frame_t>(event.data);
    if (!manifest) continue;
    if (survey.manifests++ == 0) {
      survey.width = manifest->width;
      survey.height = manifest->height;
    }
    survey.keyframes += manifest->keyframe;
    sim_times.push_back(manifest->sim_time);
  }
  survey.problem = reader.problem();
  const auto believable = [](double rate) { return rate > 0 && rate <= kMaxFrameRate; };
  if (params_rate && believable(*params_rate)) {
    survey.frame_rate = *params_rate;
    survey.frame_rate_source = "PARAMS";
  } else {
    const double estimate = EstimateFrameRate(sim_times);
    survey.frame_rate = believable(estimate) ? estimate : 0;
    survey.frame_rate_source = "FRAME times";
  }
  return survey;
}

LogFrames::LogFrames(const std::string& path, const Channels& channels, double frame_rate)
    : reader_(path), channels_(channels), frame_rate_(frame_rate) {}

// repeats first (the last image again), then the new image behind them, then read on
bool LogFrames::Next() {
  while (true) {
    if (repeats_due_ > 0) {
      --repeats_due_;
      repeated_ = true;
      ++images_;
      return true;
    }
    if (new_image_due_) {
      new_image_due_ = false;
      image_.swap(next_image_);
      width_ = next_width_;
      height_ = next_height_;
      frame_id_ = next_frame_id_;
      repeated_ = false;
      ++images_;
      return true;
    }
    if (!ReadToNextFrame()) return false;
  }
}

bool LogFrames::ReadToNextFrame() {
  const auto wanted = [this](const std::string& channel) {
    return channel == channels_.tile || channel == channels_.frame;
  };
  while (reader_.Next(&event_, wanted)) {
    if (event_.channel == channels_.tile) {
      OnTile(event_.data);
    } else if (event_.channel == channels_.frame && OnManifest(event_.data)) {
      return true;
    }
  }
  return false;
}

void LogFrames::OnTile(const std::vector<uint8_t>& data) {
  const auto tile = Decode<tile_t>(data);
  if (!tile) {
    ++report_.undecodable;
  } else if (!assembler_.AddTile(*tile).empty()) {
    ++report_.refused_tiles;
  }
}

// manifest => assembler (hash check) => skipped, dropped, or its place: repeats for the frame
// times missed, then its image (whole) or the last image again (tiles lost)
bool LogFrames::OnManifest(const std::vector<uint8_t>& data) {
  const auto manifest = Decode<frame_t>(data);
  if (!manifest) {
    ++report_.undecodable;
    return false;
  }
  const bool whole = assembler_.AddManifest(*manifest) == TileAssembler::FrameResult::kComplete;
  if (!started_) {  // from the first whole frame: a keyframe, or tiles the rolling refresh completed
    if (!whole) {
      ++report_.skipped_before_whole;
      return false;
    }
    started_ = true;
    first_time_ = last_time_ = manifest->sim_time;
  }
  const int64_t slot = FrameSlot(manifest->sim_time);
  const int64_t position = images_;  // nothing is waiting: Next() reads only then
  if (slot < position) {
    ++report_.dropped;
    return false;
  }
  repeats_due_ = slot - position;
  report_.gaps += repeats_due_;
  if (whole) {
    next_image_ = assembler_.image();
    next_width_ = assembler_.width();
    next_height_ = assembler_.height();
    next_frame_id_ = manifest->frame_id;
    new_image_due_ = true;
  } else {
    ++report_.lost;
    ++repeats_due_;
  }
  return true;
}

int64_t LogFrames::FrameSlot(double sim_time) {
  if (frame_rate_ <= 0 || !std::isfinite(sim_time)) return images_;
  const bool jumped = sim_time < last_time_ - 0.5 / frame_rate_ || sim_time > last_time_ + kMaxGapSeconds;
  last_time_ = sim_time;
  if (jumped) {  // a new session: this frame comes next, and the count goes on from it
    ++report_.time_jumps;
    first_time_ = sim_time - double(images_) / frame_rate_;
    return images_;
  }
  return std::llround((sim_time - first_time_) * frame_rate_);
}

}  // namespace flagsim
