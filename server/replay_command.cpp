#include "server/replay_command.hpp"

#include <cstdio>
#include <string>

#include "client/progress_bar.hpp"

namespace flagsim {

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

}  // namespace flagsim
