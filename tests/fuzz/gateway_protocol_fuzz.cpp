// Fuzz target: the Foxglove WebSocket protocol as a gateway of one server takes it from a client
// (gateway_session.hpp: the records, the events they are, what is checked).
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/gateway_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  flagsim::fuzz::RunGatewaySession(data, size, /*several=*/false);
  return 0;
}
