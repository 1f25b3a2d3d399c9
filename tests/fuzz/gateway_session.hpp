// What the gateway's fuzz targets share: the Foxglove WebSocket protocol as the gateway
// (flagctl serve) takes it from a client, with the command side of one server, or of two
// (ALPHA_ and BETA_) for a gateway of several, answering on an in-process bus (memq://), so that
// requests go all the way: JSON ops (subscribe, advertise, getParameters, setParameters, ...),
// binary frames (client publishes, service calls), each turned into a command, relayed to its
// server, answered by the server's ACK and replied to. Each record of the input
// (fuzz_records.hpp) is one event, as its selector says:
//
//   selector % 3 (one server) or % 4 (several)
//       0 a text message   1 a binary message
//       2 the clock moves on by the record's first byte in tenths of a second (resends,
//         timeouts, status; of several, a server without a STATUS for 5 s is withdrawn)
//       3 (several) a STATUS of the server the record's first byte picks: found, or found again
//   selector & 0x80  after it, the servers' sessions step once
//
// Checked: what the gateway sends the client (gateway_client.hpp), that every command it sends
// a server decodes there, and what the servers publish (command_server.hpp).
#pragma once

#include <cstddef>
#include <cstdint>

namespace flagsim::fuzz {

/// One input through a gateway of one server (`several` false) or of two.
void RunGatewaySession(const uint8_t* data, size_t size, bool several);

}  // namespace flagsim::fuzz
