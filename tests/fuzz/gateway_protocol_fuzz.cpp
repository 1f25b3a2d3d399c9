// Fuzz target: the Foxglove WebSocket protocol as the gateway (flagctl serve) takes it from a
// client, with the server's command side answering on an in-process bus (memq://), so that
// requests go all the way: JSON ops (subscribe, advertise, getParameters, setParameters, ...),
// binary frames (client publishes, service calls: wind, set, camera, keyframe, refresh,
// record), each turned into a command, relayed, answered by the server's ACK and replied to.
// Each record of the input (fuzz_records.hpp) is one event, as its selector says:
//
//   selector % 3   0 a text message   1 a binary message   2 the clock moves on by the
//                  record's first byte in tenths of a second (resends, timeouts, status)
//   selector & 0x80  after it, the server's session steps once
//
// Checked: what the gateway sends the client (gateway_client.hpp), that every command it sends
// the server decodes there, and what the server publishes (command_server.hpp).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "client/gateway/gateway.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/utime.hpp"
#include "server/service/message_builders.hpp"
#include "tests/fuzz/command_server.hpp"
#include "tests/fuzz/fuzz_records.hpp"
#include "tests/fuzz/gateway_client.hpp"

using namespace flagsim;

namespace {

/// Where /flag/record writes: this process's own, emptied after each input.
const std::string& RecordDirectory() {
  static const std::string directory =
      (std::filesystem::temp_directory_path() / ("flagsim-fuzz-recordings-" + std::to_string(getpid())))
          .string();
  return directory;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool quiet = (fuzz::QuietLogs(), true);
  (void)quiet;
  Bus bus("memq://");
  const Channels channels;
  fuzz::CommandServer server(bus, channels);
  double now = 0;
  gateway::GatewayOptions options;
  options.clock = [&now] { return now; };
  options.record_directory = RecordDirectory();
  {
    gateway::Gateway gateway(bus, gateway::ServerSelection::One(channels.prefix), options);
    fuzz::ReadingClient client(gateway);
    bus.Publish(channels.params, MakeParamsMessage(server.session().scene(), UnixMicros()));
    server.HandleAll();
    fuzz::Records records(data, size);
    fuzz::Record record;
    while (records.Next(&record)) {
      const std::string_view bytes(reinterpret_cast<const char*>(record.data), record.size);
      switch ((record.selector & 0x7f) % 3) {
        case 0:
          client.protocol().OnText(bytes);
          break;
        case 1:
          client.protocol().OnBinary(bytes);
          break;
        default:
          now += (record.size > 0 ? record.data[0] : 1) / 10.0;
          gateway.Tick();
          break;
      }
      server.HandleAll();
      if (server.TakeParamsChanged()) {  // as the server publishes PARAMS after a change
        bus.Publish(channels.params, MakeParamsMessage(server.session().scene(), UnixMicros()));
        server.HandleAll();
      }
      if (record.selector & 0x80) server.Step();
      client.ReadAll();
      fuzz::Require(server.stats().messages_dropped == 0,
                    "the gateway sent a command the server cannot decode");
    }
    server.Finish();
  }
  std::error_code ignored;
  std::filesystem::remove_all(RecordDirectory(), ignored);
  return 0;
}
