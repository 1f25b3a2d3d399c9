// Fuzz target: every message the clients take from the bus, through the same subscriptions
// (client/stream_reader.hpp: checked decode) and the same handlers: flagctl's (watch's state
// line, snapshot's tile assembler, the params, status and keyframe list tables, a command's ACK)
// and the gateway's (flagctl serve: the frame mirror, the JSON feeds, parameter changes, command
// answers) with a client subscribed to every channel and reading all it is sent. Each record
// of the input (fuzz_records.hpp) is one message, on the channel its selector picks:
//
//   selector % 7   0 STATE  1 TILE  2 FRAME  3 PARAMS  4 STATUS  5 TIMELINE  6 ACK
//
// TILE carries zstd of row residuals, so this is also the target of the tile decoding. What
// the gateway sends its client is checked as a Foxglove client reads it (gateway_client.hpp).
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>

#include "client/command_client.hpp"
#include "client/gateway/gateway.hpp"
#include "client/printing.hpp"
#include "client/stream_reader.hpp"
#include "client/tile_assembler.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "tests/fuzz/command_server.hpp"
#include "tests/fuzz/fuzz_records.hpp"
#include "tests/fuzz/gateway_client.hpp"

using namespace flagsim;

namespace {

/// An output stream that keeps nothing: the tables are formatted, not kept.
class NullStream : public std::ostream {
 public:
  NullStream() : std::ostream(nullptr) {}
};

/// flagctl's readers, each as its subcommand subscribes it.
struct FlagctlReaders {
  FlagctlReaders(Bus& bus, const Channels& channels) : command(bus, channels, 0.0) {
    SubscribeDecoded<state_t>(bus, channels.state, [this](const state_t& state) { out << TipText(state); });
    SubscribeDecoded<tile_t>(bus, channels.tile, [this](const tile_t& tile) { assembler.AddTile(tile); });
    SubscribeDecoded<frame_t>(bus, channels.frame,
                              [this](const frame_t& frame) { assembler.AddManifest(frame); });
    SubscribeDecoded<params_t>(bus, channels.params,
                               [this](const params_t& params) { PrintParams(params, out); });
    SubscribeDecoded<status_t>(bus, channels.status,
                               [this](const status_t& status) { PrintStatus(status, out); });
    SubscribeDecoded<timeline_t>(bus, channels.timeline,
                                 [this](const timeline_t& timeline) { PrintTimeline(timeline, out); });
  }
  NullStream out;
  TileAssembler assembler;
  CommandClient command;  ///< listens for ACKs as a command awaiting its answer does
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool quiet = (fuzz::QuietLogs(), true);
  (void)quiet;
  Bus bus("memq://");
  const Channels channels;
  double now = 0;
  gateway::GatewayOptions options;
  options.clock = [&now] { return now; };
  gateway::Gateway gateway(bus, gateway::ServerSelection::One(channels.prefix), options);
  fuzz::ReadingClient client(gateway);
  client.SubscribeAll();
  FlagctlReaders flagctl(bus, channels);
  const std::string* const sources[] = {&channels.state,  &channels.tile,   &channels.frame,
                                        &channels.params, &channels.status, &channels.timeline,
                                        &channels.ack};
  fuzz::Records records(data, size);
  fuzz::Record record;
  while (records.Next(&record)) {
    bus.Publish(*sources[record.selector % 7], record.data, record.size);
    bus.HandleAll();
    now += 0.25;
    gateway.Tick();
    client.ReadAll();
  }
  return 0;
}
