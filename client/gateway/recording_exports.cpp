#include "client/gateway/recording_exports.hpp"

#include <filesystem>

namespace flagsim::gateway {
namespace {

std::string FileName(const std::string& path) { return std::filesystem::path(path).filename().string(); }

}  // namespace

std::string ExportName(const std::string& log_name, const std::string& extension) {
  const size_t dot = log_name.rfind('.');
  return (dot == std::string::npos ? log_name : log_name.substr(0, dot)) + "." + extension;
}

RecordingExports::RecordingExports(std::vector<Format> formats)
    : formats_(std::move(formats)), worker_([this] { Run(); }) {}

RecordingExports::~RecordingExports() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

void RecordingExports::Begin(const std::string& log_path) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::filesystem::path log(log_path);
  for (const Format& format : formats_) {
    const std::string name = ExportName(log.filename().string(), format.extension);
    jobs_.push_back({log_path, (log.parent_path() / name).string(), format.extension, &format.exporter});
    states_[name] = {{"state", "waiting"}, {"error", ""}};
  }
  wake_.notify_all();
}

nlohmann::json RecordingExports::State(const std::string& log_name) const {
  std::lock_guard<std::mutex> lock(mutex_);
  nlohmann::json state = nlohmann::json::object();
  for (const Format& format : formats_) {
    const std::string name = ExportName(log_name, format.extension);
    const auto found = states_.find(name);
    if (found == states_.end()) continue;
    nlohmann::json entry = found->second;
    entry["url"] = entry["state"] == "ready" ? "/recordings/" + name : "";
    state[format.extension] = entry;
  }
  return state;
}

bool RecordingExports::Ready(const std::string& file_name) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto found = states_.find(file_name);
  return found != states_.end() && found->second["state"] == "ready";
}

// One job at a time: the exporter writes NAME.part, renamed to NAME when whole.
void RecordingExports::Run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || !jobs_.empty(); });
    if (stop_) return;
    const Job job = jobs_.front();
    jobs_.pop_front();
    const std::string name = FileName(job.output);
    states_[name]["state"] = "making";
    lock.unlock();
    const std::string part = job.output + ".part." + job.extension;  // the exporter goes by the extension
    std::string problem = (*job.exporter)(job.log_path, part, stop_);
    std::error_code error;
    if (problem.empty()) std::filesystem::rename(part, job.output, error);
    if (problem.empty() && error) problem = "cannot rename " + part + ": " + error.message();
    if (!problem.empty()) std::filesystem::remove(part, error);
    lock.lock();
    states_[name] = {{"state", problem.empty() ? "ready" : "failed"}, {"error", problem}};
  }
}

}  // namespace flagsim::gateway
