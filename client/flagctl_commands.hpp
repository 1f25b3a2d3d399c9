// What each flagctl subcommand does, once its command line is parsed (flagctl_main.cpp).
// Each returns the process's exit code: 0 ok, 1 failed (a file, ffmpeg), 2 usage, 3 rejected
// by the server (its reason printed), 4 no answer within the timeout, 5 nothing to export.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "client/gateway/serve.hpp"
#include "flagsim/camera_command_t.hpp"
#include "flagsim/keyframe_command_t.hpp"
#include "messages/channels.hpp"
#include "messages/command_mac.hpp"

namespace flagsim {

enum ExitCode { kOk = 0, kFailed = 1, kUsage = 2, kRejected = 3, kNoAnswer = 4, kNothingToExport = 5 };

/// Set by SIGINT / SIGTERM: watch and record stop and report.
extern std::atomic<bool> g_stop;

/// Options every subcommand takes.
struct Globals {
  std::string lcm_url;
  std::string prefix = Channels::kDefaultPrefix;
  double timeout = 2.0;  ///< s to wait for an answer
  CommandSigner signer;  ///< signs every command sent (--key-file); unsigned by default
};

int Wind(const Globals& globals, const std::vector<double>& velocity, double gust, double ramp);
/// PARAM assignments "NAME=VALUE"; `reset` first restores the scene.
int Set(const Globals& globals, const std::vector<std::string>& assignments, bool reset);
int Refresh(const Globals& globals);
int Params(const Globals& globals);
int Status(const Globals& globals);
/// A line a second about the streams until `duration` s (0: until interrupted).
int Watch(const Globals& globals, double duration);
/// A keyframe, assembled and hash-checked, written as a PNG.
int Snapshot(const Globals& globals, const std::string& path);
int Camera(const Globals& globals, camera_command_t command);
/// One KEYFRAME command (flagctl_keyframe.hpp builds it from the command line).
int SendKeyframe(const Globals& globals, const keyframe_command_t& command);
/// The next TIMELINE message, printed: play state and every key with what it sets.
int Timeline(const Globals& globals);
/// Every channel with the prefix into an LCM log until `duration` s (0: until interrupted).
int Record(const Globals& globals, const std::string& path, double duration);

struct ExportRequest {
  std::string log_path;   ///< an LCM event log
  std::string output;     ///< DIR/ (PNG frames), NAME.mp4 or NAME.gif
  double frame_rate = 0;  ///< Hz of the video; 0: the log's own
};
/// The frames in a log, assembled and hash-checked, into PNGs or a video (flagctl_export.cpp).
int Export(const Globals& globals, const ExportRequest& request);

/// A new key file at `path` holding one key named `name` (flagctl_keygen.cpp).
int Keygen(const std::string& path, const std::string& name);

/// The live view's gateway, until interrupted (flagctl_serve.cpp).
int Serve(const Globals& globals, const gateway::ServeOptions& options);

}  // namespace flagsim
