// What the gateway says of itself, once a second and on each change: /gateway/status (its
// clients, refusals, CPU and memory, and the servers' streams summed) and /gateway/servers (each
// server it serves, as ServerLink::Summary has it). Rates cover the window since the last status.
#include "client/gateway/bus_json.hpp"
#include "client/gateway/gateway.hpp"
#include "client/gateway/process_usage.hpp"

namespace flagsim::gateway {

using nlohmann::json;

void Gateway::PublishServers() {
  json servers = json::array();
  for (const auto& [prefix, slot] : slots_) {
    servers.push_back(links_.at(slot)->Summary(offered_.count(slot) > 0, frames_per_second_[slot]));
  }
  servers_feed_.Publish(Nanoseconds(UnixMicros()), JsonText({{"servers", servers}}));
  WakeAll();
}

void Gateway::PublishGatewayStatus(double now) {
  const double window = std::max(now - status_window_start_, 1e-3);
  json per_client = json::array();
  double bytes_per_second = 0;
  for (auto& [id, client] : clients_) {
    const ClientCounters& counters = client->protocol().counters();
    const ClientCounters before = counters_at_window_[id];
    const double rate = double(counters.bytes_sent - before.bytes_sent) / window;
    bytes_per_second += rate;
    per_client.push_back({{"id", id},
                          {"address", client->address()},
                          {"bytes_per_second", rate},
                          {"frames_per_second", double(counters.frames_sent - before.frames_sent) / window},
                          {"frames_skipped", counters.frames_skipped},
                          {"queued_bytes", client->protocol().queued_bytes()}});
    counters_at_window_[id] = counters;
  }
  ServerLinkCounters servers;
  double frames_per_second = 0;
  for (const auto& [slot, link] : links_) {
    const ServerLinkCounters& its = link->counters();
    servers.incomplete_frames += its.incomplete_frames;
    servers.server_restarts += its.server_restarts;
    servers.bus_undecodable += its.bus_undecodable;
    frames_per_second_[slot] = double(its.frames_mirrored - frames_at_window_[slot]) / window;
    frames_per_second += frames_per_second_[slot];
    frames_at_window_[slot] = its.frames_mirrored;
  }
  const ProcessUsage usage = ReadProcessUsage();
  const json status = {{"uptime", now - started_},
                       {"clients", clients_.size()},
                       {"clients_dropped", counters_.clients_dropped},
                       {"unauthorized", counters_.unauthorized},
                       {"forbidden", counters_.forbidden},
                       {"protocol_errors", counters_.protocol_errors},
                       {"servers", offered_.size()},
                       {"servers_ignored", counters_.servers_ignored},
                       {"frames_per_second", frames_per_second},
                       {"incomplete_frames", servers.incomplete_frames},
                       {"server_restarts", servers.server_restarts},
                       {"bus_undecodable", servers.bus_undecodable},
                       {"cpu_seconds", usage.cpu_seconds},
                       {"resident_bytes", usage.resident_bytes},
                       {"bytes_per_second", bytes_per_second},
                       {"per_client", per_client}};
  status_window_start_ = now;
  status_feed_.Publish(Nanoseconds(UnixMicros()), JsonText(status));
  PublishServers();
}

}  // namespace flagsim::gateway
