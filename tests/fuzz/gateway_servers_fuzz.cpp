// Fuzz target: the Foxglove WebSocket protocol as a gateway of several servers takes it from a
// client, with two servers found by their STATUS (ALPHA_ in slot 1, BETA_ in slot 2), withdrawn
// when the clock passes 5 s without one, and found again (gateway_session.hpp).
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/gateway_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  flagsim::fuzz::RunGatewaySession(data, size, /*several=*/true);
  return 0;
}
