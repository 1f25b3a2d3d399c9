#include "tests/fuzz/gateway_session.hpp"

#include <unistd.h>

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "client/gateway/gateway.hpp"
#include "flagsim/status_t.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/utime.hpp"
#include "server/service/message_builders.hpp"
#include "tests/fuzz/command_server.hpp"
#include "tests/fuzz/fuzz_records.hpp"
#include "tests/fuzz/gateway_client.hpp"

namespace flagsim::fuzz {
namespace {

/// Where /flag/record writes: this process's own, emptied after each input.
const std::string& RecordDirectory() {
  static const std::string directory =
      (std::filesystem::temp_directory_path() / ("flagsim-fuzz-recordings-" + std::to_string(getpid())))
          .string();
  return directory;
}

/// A server's command side and its channels, which it keeps by reference.
struct FuzzedServer {
  FuzzedServer(Bus& bus, const std::string& prefix) : channels(prefix), server(bus, channels) {}
  Channels channels;
  CommandServer server;
};

void PublishParams(Bus& bus, FuzzedServer& fuzzed) {
  bus.Publish(fuzzed.channels.params, MakeParamsMessage(fuzzed.server.session().scene(), UnixMicros()));
  fuzzed.server.HandleAll();
}

/// The STATUS by which a gateway of several finds a server.
void PublishStatus(Bus& bus, FuzzedServer& fuzzed, int64_t server_id) {
  status_t status{};
  status.utime = UnixMicros();
  status.server_id = server_id;
  bus.Publish(fuzzed.channels.status, status);
  fuzzed.server.HandleAll();
}

}  // namespace

void RunGatewaySession(const uint8_t* data, size_t size, bool several) {
  static const bool quiet = (QuietLogs(), true);
  (void)quiet;
  Bus bus("memq://");
  std::vector<std::unique_ptr<FuzzedServer>> servers;
  for (const char* prefix : several ? std::vector<const char*>{"ALPHA_", "BETA_"}
                                    : std::vector<const char*>{Channels::kDefaultPrefix}) {
    servers.push_back(std::make_unique<FuzzedServer>(bus, prefix));
  }
  double now = 0;
  gateway::GatewayOptions options;
  options.clock = [&now] { return now; };
  options.record_directory = RecordDirectory();
  {
    const gateway::ServerSelection selection = several
                                                   ? gateway::ServerSelection::Many({})
                                                   : gateway::ServerSelection::One(Channels::kDefaultPrefix);
    gateway::Gateway gateway(bus, selection, options);
    ReadingClient client(gateway);
    for (size_t i = 0; i < servers.size(); ++i) {
      if (several) PublishStatus(bus, *servers[i], int64_t(i) + 1);
      PublishParams(bus, *servers[i]);
    }
    Records records(data, size);
    Record record;
    while (records.Next(&record)) {
      const std::string_view bytes(reinterpret_cast<const char*>(record.data), record.size);
      const uint8_t first = record.size > 0 ? record.data[0] : 1;
      switch ((record.selector & 0x7f) % (several ? 4 : 3)) {
        case 0:
          client.protocol().OnText(bytes);
          break;
        case 1:
          client.protocol().OnBinary(bytes);
          break;
        case 2:
          now += first / 10.0;
          gateway.Tick();
          break;
        default:
          PublishStatus(bus, *servers[first % servers.size()], first % servers.size() + 1);
          break;
      }
      for (auto& fuzzed : servers) {
        fuzzed->server.HandleAll();
        if (fuzzed->server.TakeParamsChanged()) PublishParams(bus, *fuzzed);  // as a server publishes PARAMS
        if (record.selector & 0x80) fuzzed->server.Step();
        Require(fuzzed->server.stats().messages_dropped == 0,
                "the gateway sent a command the server cannot decode");
      }
      client.ReadAll();
    }
    for (auto& fuzzed : servers) fuzzed->server.Finish();
  }
  std::error_code ignored;
  std::filesystem::remove_all(RecordDirectory(), ignored);
}

}  // namespace flagsim::fuzz
