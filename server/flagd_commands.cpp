#include "server/flagd_commands.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>

#include "server/parallel/worker_pool.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/scene/scene_file.hpp"

namespace flagsim {

// Logs go to stderr, as a command's diagnostics do; stdout is for what a command reports.
// Beside a busy neighbour, loops shared among more threads than the free cores run slower than on
// one thread: they are shared among the free cores only.
void FlagdInvocation::RunOnParse(CLI::App* command, std::function<int()> run) {
  command->callback([this, run = std::move(run)] {
    spdlog::set_default_logger(
        std::make_shared<spdlog::logger>("", std::make_shared<spdlog::sinks::stderr_color_sink_mt>()));
    spdlog::set_level(spdlog::level::from_str(globals.log_level));
    WorkerPool::Shared().ShareFreeCoresOnly(true);
    exit_code = run();
  });
}

bool FlagdInvocation::StartsAServer() const {
  if (resume == nullptr || resume->count() == 0) return false;
  std::fprintf(stderr, "flagd: --resume starts a server; it does not go with render or replay\n");
  return true;
}

Scene BuildScene(const FlagdGlobals& globals) {
  Scene scene = LoadScene(globals.scene);
  for (const std::string& assignment : globals.assignments) {
    const size_t equals = assignment.find('=');
    if (equals == std::string::npos) throw SceneError("--set " + assignment + ": expected NAME=VALUE");
    const std::string problem =
        ParameterTable::Get().Assign(assignment.substr(0, equals), assignment.substr(equals + 1), &scene);
    if (!problem.empty()) throw SceneError("--set " + problem);
  }
  ParameterTable::SettleAutoModel(&scene);
  const std::string problem = ParameterTable::CheckConsistency(scene);
  if (!problem.empty()) throw SceneError(problem);
  return scene;
}

}  // namespace flagsim
