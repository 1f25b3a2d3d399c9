// chaos_client: the soak's unruly user. Sends random valid and invalid commands of every kind
// (soak/chaos_commands.hpp) to a server, one at a time: each is resent until answered or until
// --timeout, and the next goes out a random pause after the answer, so the server is never asked
// for more than its answer limits allow and owes every command an answer. Counts, per kind, what
// was sent, accepted, rejected and left unanswered, and the surprises: an invalid command
// accepted (a hole in validation), a valid one rejected (the region's edge, or a key removed
// before it was changed); prints a table and writes it as JSON.
//   chaos_client [--lcm-url URL] [--prefix P] --duration S [--seed N] [--invalid F] [--report FILE]
#include <CLI/CLI.hpp>
#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "bench/soak/chaos_commands.hpp"
#include "client/command_client.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"

namespace flagsim::soak {
namespace {

std::atomic<bool> stop_requested{false};
void OnSignal(int) { stop_requested = true; }

struct Tally {
  int64_t sent = 0, accepted = 0, rejected = 0, unanswered = 0;
  int64_t invalid_accepted = 0, valid_rejected = 0;
  std::string last_surprise;  ///< the latest surprise, with the server's reason
};

/// The channel a command of this type goes on.
const std::string& ChannelOf(const Channels& channels, const ChaosMessage& message) {
  switch (message.index()) {
    case 0:
      return channels.wind;
    case 1:
      return channels.param;
    case 2:
      return channels.camera;
    case 3:
      return channels.keyframe;
    default:
      return channels.refresh;
  }
}

void Count(const ChaosCommand& command, const CommandOutcome& outcome, Tally* tally) {
  ++tally->sent;
  if (outcome.result == CommandOutcome::kNoAnswer) {
    ++tally->unanswered;
    tally->last_surprise = command.what + ": no answer";
  } else if (outcome.result == CommandOutcome::kAccepted) {
    ++tally->accepted;
    if (!command.valid) ++tally->invalid_accepted, tally->last_surprise = command.what + ": accepted";
  } else {
    ++tally->rejected;
    if (command.valid) ++tally->valid_rejected, tally->last_surprise = command.what + ": " + outcome.reason;
  }
}

nlohmann::json Report(const std::array<Tally, kChaosKinds>& tallies, double seconds) {
  nlohmann::json report = {{"seconds", seconds}, {"kinds", nlohmann::json::array()}};
  Tally all;
  for (int kind = 0; kind < kChaosKinds; ++kind) {
    const Tally& tally = tallies[kind];
    report["kinds"].push_back({{"kind", ChaosKindName(ChaosKind(kind))},
                               {"sent", tally.sent},
                               {"accepted", tally.accepted},
                               {"rejected", tally.rejected},
                               {"unanswered", tally.unanswered},
                               {"invalid_accepted", tally.invalid_accepted},
                               {"valid_rejected", tally.valid_rejected},
                               {"last_surprise", tally.last_surprise}});
    all.sent += tally.sent, all.accepted += tally.accepted, all.rejected += tally.rejected;
    all.unanswered += tally.unanswered, all.invalid_accepted += tally.invalid_accepted;
    all.valid_rejected += tally.valid_rejected;
  }
  report["total"] = {{"sent", all.sent},
                     {"accepted", all.accepted},
                     {"rejected", all.rejected},
                     {"unanswered", all.unanswered},
                     {"invalid_accepted", all.invalid_accepted},
                     {"valid_rejected", all.valid_rejected}};
  return report;
}

void Print(const nlohmann::json& report) {
  std::printf("%-17s %7s %9s %9s %11s %17s %15s\n", "kind", "sent", "accepted", "rejected", "unanswered",
              "invalid accepted", "valid rejected");
  const auto row = [](const std::string& name, const nlohmann::json& t) {
    std::printf("%-17s %7lld %9lld %9lld %11lld %17lld %15lld\n", name.c_str(), t["sent"].get<long long>(),
                t["accepted"].get<long long>(), t["rejected"].get<long long>(),
                t["unanswered"].get<long long>(), t["invalid_accepted"].get<long long>(),
                t["valid_rejected"].get<long long>());
  };
  for (const auto& kind : report["kinds"]) row(kind["kind"], kind);
  row("all", report["total"]);
  for (const auto& kind : report["kinds"]) {
    if (!kind["last_surprise"].get<std::string>().empty())
      std::printf("  %s, last surprise: %s\n", kind["kind"].get<std::string>().c_str(),
                  kind["last_surprise"].get<std::string>().c_str());
  }
}

}  // namespace
}  // namespace flagsim::soak

int main(int argc, char** argv) {
  using namespace flagsim;
  using namespace flagsim::soak;
  std::string url, prefix = Channels::kDefaultPrefix, report_path;
  double duration = 60, invalid = 0.25, timeout = 10, pause_low = 0.05, pause_high = 0.3;
  uint64_t seed = 1;
  CLI::App app{"chaos_client: random valid and invalid commands, one at a time, each answer awaited"};
  app.add_option("--lcm-url", url, "LCM URL (default: $LCM_DEFAULT_URL, else LCM's)");
  app.add_option("--prefix", prefix, "channel prefix of the server")->capture_default_str();
  app.add_option("--duration", duration, "seconds to run")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--seed", seed, "seed of the random commands")->capture_default_str();
  app.add_option("--invalid", invalid, "fraction of commands that break a rule")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--timeout", timeout, "seconds to wait for each answer")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--report", report_path, "write the tally here as JSON");
  CLI11_PARSE(app, argc, argv);
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);

  Bus bus(url);
  const Channels channels(prefix);
  CommandClient client(bus, channels, timeout);
  ChaosCommands commands(seed, invalid);
  std::mt19937 pauses(seed + 1);
  std::array<Tally, kChaosKinds> tallies;
  const double start = MonotonicSeconds();
  while (!stop_requested && MonotonicSeconds() - start < duration) {
    const ChaosCommand command = commands.Next();
    const CommandOutcome outcome = std::visit(
        [&](const auto& message) { return client.Send(ChannelOf(channels, command.message), message); },
        command.message);
    Count(command, outcome, &tallies[int(command.kind)]);
    const double pause = std::uniform_real_distribution<double>(pause_low, pause_high)(pauses);
    std::this_thread::sleep_for(std::chrono::duration<double>(pause));
  }
  const nlohmann::json report = Report(tallies, MonotonicSeconds() - start);
  Print(report);
  if (!report_path.empty()) std::ofstream(report_path) << report.dump(2) << "\n";
  return report["total"]["unanswered"].get<int64_t>() == 0 ? 0 : 1;
}
