// Fuzz target: every message flagd takes from the bus, through its real intake. Each record of
// the input (fuzz_records.hpp) is one message, published on an in-process bus (memq://) on the
// channel its selector picks:
//
//   (selector & 0x7f) % 8   0 WIND  1 PARAM  2 CAMERA  3 KEYFRAME  4 REFRESH   (command_intake.hpp)
//                          5 STATUS (another server's, as server_presence.hpp hears it)
//                          6 TIME  7 DESIGN (a piece of a person's image)
//   selector & 0x80  after it, the session steps once (a playing timeline, settling ACKs)
//
// and taken as flagd takes it: checked decode, validation, apply, ACK, journal. What the server
// publishes in answer is checked as its readers take it (command_server.hpp).
#include <cstddef>
#include <cstdint>
#include <string>

#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "tests/fuzz/command_server.hpp"
#include "tests/fuzz/fuzz_records.hpp"

using namespace flagsim;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool quiet = (fuzz::QuietLogs(), true);
  (void)quiet;
  Bus bus("memq://");
  const Channels channels;
  fuzz::CommandServer server(bus, channels);
  const std::string* const targets[] = {&channels.wind,     &channels.param,   &channels.camera,
                                        &channels.keyframe, &channels.refresh, &channels.status,
                                        &channels.time,     &channels.design};
  fuzz::Records records(data, size);
  fuzz::Record record;
  while (records.Next(&record)) {
    bus.Publish(*targets[(record.selector & 0x7f) % 8], record.data, record.size);
    server.HandleAll();
    if (record.selector & 0x80) server.Step();
  }
  server.Finish();
  return 0;
}
