// flagd replay LOG: a recorded session stepped again from its log (service/replay.hpp), every
// recorded state hash checked; the command line's side: its options, the progress bar and the verdict.
#include <cstdio>
#include <memory>
#include <string>

#include "common/progress_bar.hpp"
#include "server/flagd_commands.hpp"
#include "server/service/replay.hpp"

namespace flagsim {
namespace {

/// Replays the log at `path` and prints what it found. Returns the exit code: 0 every recorded
/// hash equal, 1 a difference (the first is printed), 2 nothing to replay (no checkpoint, a log
/// that cannot be read).
int RunReplay(const std::string& path, const ReplayOptions& options) {
  ProgressBar bar;
  const ReplayReport report =
      Replay(path, options, [&bar](double fraction) { bar.Update(fraction, "replaying"); });
  if (!report.error.empty()) {
    bar.Finish("flagd replay: " + report.error);
    return 2;
  }
  bar.Finish("flagd replay: " + path + ": resumed at step " + std::to_string(report.first_step) + " (" +
             report.first_reason + " checkpoint), replayed to step " + std::to_string(report.last_step) +
             " on " + std::to_string(report.threads) + " thread(s): " + std::to_string(report.commands) +
             " command(s) and " + std::to_string(report.model_switches) + " switch(es) of auto's model applied, " + std::to_string(report.states_checked) + " state and " +
             std::to_string(report.checkpoints_checked) + " checkpoint hash(es) checked");
  std::fprintf(stderr, "flagd replay: the first checkpoint's state hash %016llx",
               static_cast<unsigned long long>(report.first_hash));
  if (report.last_checkpoint_step >= 0) {
    std::fprintf(stderr, "; the last checked: step %lld, state hash %016llx",
                 static_cast<long long>(report.last_checkpoint_step),
                 static_cast<unsigned long long>(report.last_checkpoint_hash));
  }
  std::fprintf(stderr, "\n");
  if (!report.log_end.empty())
    std::fprintf(stderr, "flagd replay: the log ends early: %s\n", report.log_end.c_str());
  if (!report.divergence.empty()) {
    std::fprintf(stderr, "flagd replay: first difference: %s\n", report.divergence.c_str());
    return 1;
  }
  std::fprintf(stderr, "flagd replay: every hash equal, bit for bit\n");
  return 0;
}

}  // namespace

void AddReplayCommand(CLI::App& app, FlagdInvocation& invocation) {
  auto log = std::make_shared<std::string>();
  auto options = std::make_shared<ReplayOptions>();
  CLI::App* replay = app.add_subcommand(
      "replay",
      "step a recorded session again from its log (its first CHECKPOINT, then the APPLIED commands at "
      "their steps) and check every recorded state hash bit for bit; exit 0 all equal, 1 a difference, "
      "2 nothing to replay");
  replay->add_option("log", *log, "the LCM log (flagctl record, lcm-logger, flagd render)")->required();
  replay->add_option("--threads", options->threads, "worker threads (default: as recorded)")->check(CLI::Range(1, 64));
  replay->footer("--prefix is the channels' prefix in the log.");
  invocation.RunOnParse(replay, [&invocation, log, options] {
    if (invocation.StartsAServer()) return int(kFlagdUsage);
    options->prefix = invocation.globals.prefix;
    return RunReplay(*log, *options);
  });
}

}  // namespace flagsim
