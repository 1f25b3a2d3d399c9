#include "client/gateway/session_recorder.hpp"

#include <sys/stat.h>

#include <cctype>
#include <ctime>
#include <filesystem>

namespace flagsim::gateway {
namespace {

/// "STEM-20261123-204501.lcmlog", local time.
std::string NewLogName(const std::string& stem) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char time[32];
  std::strftime(time, sizeof(time), "%Y%m%d-%H%M%S", &local);
  return stem + "-" + time + ".lcmlog";
}

bool PlainName(std::string_view name) {
  if (name.empty() || name.size() > 128 || name.front() == '.') return false;
  for (char c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.')) return false;
  }
  return true;
}

bool IsLog(std::string_view name) { return name.size() > 7 && name.substr(name.size() - 7) == ".lcmlog"; }

}  // namespace

SessionRecorder::SessionRecorder(Bus& bus, const Channels& channels, std::string directory,
                                 std::vector<RecordingExports::Format> formats, std::string stem)
    : bus_(bus),
      channels_(channels),
      directory_(std::move(directory)),
      stem_(std::move(stem)),
      exports_(std::move(formats)) {}

SessionRecorder::~SessionRecorder() = default;

nlohmann::json SessionRecorder::Start(double now) {
  if (recorder_) return State(now, "a recording is already running: " + name_);
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  if (error) return State(now, "cannot make the directory " + directory_ + ": " + error.message());
  std::string name = NewLogName(stem_);
  for (int n = 2; std::filesystem::exists(directory_ + "/" + name); ++n) {
    name = NewLogName(stem_);
    name.insert(name.size() - 7, "-" + std::to_string(n));
  }
  try {
    recorder_ = std::make_unique<LogRecorder>(bus_, channels_, directory_ + "/" + name);
  } catch (const std::exception& failure) {
    return State(now, failure.what());
  }
  name_ = name;
  started_ = now;
  last_error_.clear();
  return State(now);
}

nlohmann::json SessionRecorder::Stop(double now) {
  if (!recorder_) return State(now, "no recording is running");
  last_events_ = recorder_->events();
  last_bytes_ = recorder_->bytes();
  if (recorder_->failed()) last_error_ = recorder_->error();  // the disk is full: whole up to there
  recorder_.reset();                                          // closes the log
  stopped_ = now;
  exports_.Begin(directory_ + "/" + name_);
  return State(now);
}

bool SessionRecorder::StopIfDone(double now) {
  if (!recorder_ || (!recorder_->failed() && recorder_->bytes() < kMaxBytes)) return false;
  Stop(now);
  if (last_error_.empty()) last_error_ = "stopped at " + std::to_string(kMaxBytes >> 30) + " GiB";
  return true;
}

nlohmann::json SessionRecorder::Status(double now) const { return State(now); }

nlohmann::json SessionRecorder::State(double now, const std::string& error) const {
  const bool running = recorder_ != nullptr;
  nlohmann::json state = {
      {"recording", running},
      {"file", name_},
      {"url", !running && !name_.empty() ? "/recordings/" + name_ : ""},
      {"events", running ? recorder_->events() : last_events_},
      {"bytes", running ? recorder_->bytes() : last_bytes_},
      {"seconds", name_.empty() ? 0.0 : (running ? now : stopped_) - started_},
      {"error", error.empty() ? last_error_ : error},
      {"exports", running || name_.empty() ? nlohmann::json::object() : exports_.State(name_)}};
  return state;
}

std::optional<std::string> SessionRecorder::FinishedFile(std::string_view name) const {
  if (!PlainName(name) || (recorder_ && name == name_)) return std::nullopt;
  if (name.substr(0, stem_.size() + 1) != stem_ + "-") return std::nullopt;  // another recorder's
  if (!IsLog(name) && !exports_.Ready(std::string(name))) return std::nullopt;
  const std::string path = directory_ + "/" + std::string(name);
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode)) return std::nullopt;
  return path;
}

}  // namespace flagsim::gateway
