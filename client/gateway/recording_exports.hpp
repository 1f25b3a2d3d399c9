// A finished recording turned into the files people open without flagsim: MCAP for Foxglove and
// Lichtblick (mcap_export.hpp) and, where the gateway was given one, a video (flagctl export's
// MP4). They are made one after another on a thread of their own, so the gateway's loop never
// waits for them, each into NAME.part first and renamed when whole: a file served for download
// is always a finished one.
//
//   SessionRecorder stops NAME.lcmlog ==> Begin ==> worker: NAME.mcap, then NAME.mp4
//   /flag/record status ==> State(NAME): per format waiting, making, ready (with its url) or failed
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

namespace flagsim::gateway {

class RecordingExports {
 public:
  /// Writes `output` from the log at `log`; "" or what went wrong. `stop` asks it to end early.
  using Exporter = std::function<std::string(const std::string& log, const std::string& output,
                                             const std::atomic<bool>& stop)>;
  struct Format {
    std::string extension;  ///< "mcap", "mp4"
    Exporter exporter;
  };

  explicit RecordingExports(std::vector<Format> formats);
  ~RecordingExports();  ///< stops the export under way and waits for the thread

  /// Queues every format of the finished log at `log_path` (DIR/NAME.lcmlog).
  void Begin(const std::string& log_path);
  /// {"mcap": {"state": "waiting" | "making" | "ready" | "failed", "url", "error"}, ...} for the
  /// log named `log_name`; {} for one never begun.
  nlohmann::json State(const std::string& log_name) const;
  /// Whether `file_name` (NAME.mcap) is a finished export of a log this gateway recorded.
  bool Ready(const std::string& file_name) const;

 private:
  struct Job {
    std::string log_path, output, extension;
    const Exporter* exporter;
  };
  void Run();

  std::vector<Format> formats_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Job> jobs_;
  std::map<std::string, nlohmann::json> states_;  ///< by output file name: {"state", "error"}
  std::atomic<bool> stop_{false};
  std::thread worker_;  ///< last: started once the rest is made
};

/// "flagsim-1.lcmlog", "mcap" => "flagsim-1.mcap".
std::string ExportName(const std::string& log_name, const std::string& extension);

}  // namespace flagsim::gateway
