// Fuzz target: the signed-command envelope of a server with keys (flagd --key-file): key id,
// MAC, freshness and replay (command_authenticator.hpp), through the real intake on an
// in-process bus. Each record of the input (fuzz_records.hpp) is one command:
//
//   selector       (selector & 0x7f) % 8: 0 WIND  1 PARAM  2 CAMERA  3 KEYFRAME  4, 5 REFRESH
//                  6 TIME  7 DESIGN;
//                  & 0x80: the session steps once after it
//   bytes          how (1 byte) | utime offset (4 bytes, ms, little-endian, signed) | command
//
// With `how` bit 0 set and a decodable command, the command is stamped as a client's signer
// stamps it (command_mac.hpp): dated now plus the offset, named and signed by the server's key
// number (how bit 1), or by a key the server does not have (bit 2); bit 3 spoils the MAC's byte
// how >> 5. Bit 4 instead sends the last message sent again, byte for byte (a capture replayed).
// Otherwise the bytes go as they are. So the fuzzer reaches every refusal (unsigned, unknown
// key, bad MAC, stale, replayed) and what passes them. What the server publishes is checked as in
// server_commands.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/checked_decode.hpp"
#include "messages/command_key.hpp"
#include "messages/command_mac.hpp"
#include "messages/publisher.hpp"
#include "messages/utime.hpp"
#include "server/service/command_intake.hpp"
#include "tests/fuzz/command_server.hpp"
#include "tests/fuzz/fuzz_records.hpp"

using namespace flagsim;

namespace {

CommandKey Key(const std::string& name, uint8_t fill) {
  CommandKey key;
  key.name = name;
  for (size_t k = 0; k < key.secret.size(); ++k) key.secret[k] = uint8_t(fill + 7 * k);
  return key;
}

/// The server's two keys, then one it does not have.
const std::vector<CommandKey>& Keys() {
  static const std::vector<CommandKey> keys = {Key("alpha", 1), Key("beta", 101), Key("stranger", 201)};
  return keys;
}

struct Envelope {
  bool again = false;  ///< the last message sent, again
  bool sign = false;
  size_t key = 0;         ///< index into Keys()
  int64_t offset_us = 0;  ///< utime - now
  int spoiled_byte = -1;  ///< of the MAC, or -1
};

/// The envelope's 5 bytes at the start of `record`; false if there are fewer.
bool ReadEnvelope(const fuzz::Record& record, Envelope* envelope) {
  if (record.size < 5) return false;
  const uint8_t how = record.data[0];
  int32_t offset_ms = 0;
  for (int k = 3; k >= 0; --k) offset_ms = int32_t(uint32_t(offset_ms) << 8 | record.data[1 + k]);
  envelope->again = how & 16;
  envelope->sign = how & 1;
  envelope->key = (how & 4) ? 2 : (how >> 1) & 1;
  envelope->offset_us = int64_t(offset_ms) * 1000;
  envelope->spoiled_byte = (how & 8) ? how >> 5 : -1;
  return true;
}

/// The command in `bytes`, stamped and signed as `envelope` says, for `channel`; bytes that are
/// no Command, or that are not to be signed, as they are.
template <class Command>
std::vector<uint8_t> Stamp(const std::string& channel, const Envelope& envelope, const uint8_t* bytes,
                           size_t size) {
  std::string error;
  std::optional<Command> command =
      wire::CheckedDecode<Command>(bytes, size, CommandIntake::kMaxCommandBytes, &error);
  if (!command || !envelope.sign) return std::vector<uint8_t>(bytes, bytes + size);
  const CommandKey& key = Keys()[envelope.key];
  command->utime = UnixMicros() + envelope.offset_us;
  command->key_id = key.name;
  Mac mac = MacOf(key, channel, *command);
  if (envelope.spoiled_byte >= 0) mac[size_t(envelope.spoiled_byte)] ^= 0x01;
  std::copy(mac.begin(), mac.end(), std::begin(command->mac));
  return Publisher::Encode(*command);
}

/// The bytes of a record's command as they go onto the bus.
std::vector<uint8_t> Stamp(const Channels& channels, const std::string& channel, const Envelope& envelope,
                           const uint8_t* bytes, size_t size) {
  if (channel == channels.wind) return Stamp<wind_command_t>(channel, envelope, bytes, size);
  if (channel == channels.param) return Stamp<param_command_t>(channel, envelope, bytes, size);
  if (channel == channels.camera) return Stamp<camera_command_t>(channel, envelope, bytes, size);
  if (channel == channels.keyframe) return Stamp<keyframe_command_t>(channel, envelope, bytes, size);
  if (channel == channels.time) return Stamp<time_command_t>(channel, envelope, bytes, size);
  if (channel == channels.design) return Stamp<design_piece_t>(channel, envelope, bytes, size);
  return Stamp<refresh_request_t>(channel, envelope, bytes, size);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool quiet = (fuzz::QuietLogs(), true);
  (void)quiet;
  Bus bus("memq://");
  const Channels channels;
  fuzz::CommandServer server(bus, channels, {Keys()[0], Keys()[1]});
  // The selectors of server_commands (make_corpus.cpp); its STATUS slot is a REFRESH here.
  const std::string* const targets[] = {&channels.wind,     &channels.param,   &channels.camera,
                                        &channels.keyframe, &channels.refresh, &channels.refresh,
                                        &channels.time,     &channels.design};
  std::string last_channel;
  std::vector<uint8_t> last_sent;
  fuzz::Records records(data, size);
  fuzz::Record record;
  while (records.Next(&record)) {
    Envelope envelope;
    if (!ReadEnvelope(record, &envelope)) continue;
    if (!envelope.again || last_sent.empty()) {
      last_channel = *targets[(record.selector & 0x7f) % 8];
      last_sent = Stamp(channels, last_channel, envelope, record.data + 5, record.size - 5);
    }
    bus.Publish(last_channel, last_sent.data(), last_sent.size());
    server.HandleAll();
    if (record.selector & 0x80) server.Step();
  }
  server.Finish();
  return 0;
}
