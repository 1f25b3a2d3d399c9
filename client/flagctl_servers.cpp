// flagctl servers: the servers on the bus, found by their STATUS (once a second each) on any
// prefix, one line each: what a user of replicas started with `flagd --prefix auto` needs to
// address one of them.
#include <cstdio>
#include <cstring>
#include <map>
#include <string>

#include "client/flagctl_commands.hpp"
#include "client/stream_reader.hpp"
#include "flagsim/status_t.hpp"

namespace flagsim {
namespace {

constexpr char kStatus[] = "STATUS";

/// STATUS of every prefix heard within `timeout` s, the newest of each, by prefix.
std::map<std::string, status_t> HearServers(Bus& bus, double timeout) {
  std::map<std::string, status_t> heard;
  BusSubscriptions subscriptions(bus);
  subscriptions.Subscribe("[A-Za-z0-9_]+" + std::string(kStatus), [&heard](const std::string& channel,
                                                                           const uint8_t* data, size_t size) {
    std::string error;
    const std::optional<status_t> status =
        wire::CheckedDecode<status_t>(data, size, kMaxStreamMessageBytes, &error);
    const std::string prefix = channel.substr(0, channel.size() - std::strlen(kStatus));
    if (status && Channels::CheckPrefix(prefix).empty()) heard[prefix] = *status;
  });
  HandleUntil(bus, timeout, [] { return false; });
  return heard;
}

const char* StateOf(const status_t& status) {
  if (status.paused) return "paused";
  return status.sleeping ? "sleeping" : "running";
}

int ListServers(const Globals& globals) {
  Bus bus(globals.lcm_url);
  const std::map<std::string, status_t> servers = HearServers(bus, globals.timeout);
  if (servers.empty()) {
    std::fprintf(stderr, "flagctl servers: no server's STATUS on %s within %g s\n", bus.url().c_str(),
                 globals.timeout);
    return kNoAnswer;
  }
  std::printf("%-24s %10s %10s %9s %7s %-18s %8s %s\n", "prefix", "uptime s", "sim time s", "real time",
              "nodes", "integrator", "frames/s", "state");
  for (const auto& [prefix, status] : servers) {
    std::printf("%-24s %10.1f %10.2f %9.3f %7d %-18s %8.1f %s\n", prefix.c_str(), status.uptime,
                status.sim_time, status.real_time_factor, status.num_nodes, status.integrator.c_str(),
                status.frame_rate_hz, StateOf(status));
  }
  return kOk;
}

}  // namespace

void AddServersCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* servers = app.add_subcommand(
      "servers", "list the servers on the bus, on any prefix (each one's STATUS heard within --timeout)");
  invocation.RunOnParse(servers, [&invocation] { return ListServers(invocation.globals); });
}

}  // namespace flagsim
