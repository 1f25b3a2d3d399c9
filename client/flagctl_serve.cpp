// flagctl serve: the live view's gateway (client/gateway/serve.hpp) on the bus of the globals.
#include <cstdio>

#include "client/flagctl_commands.hpp"
#include "client/gateway/serve.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"

namespace flagsim {

int Serve(const Globals& globals, const gateway::ServeOptions& options) {
  // A deep receive buffer: frames arrive as bursts of tiles (as for every flagctl reader).
  Bus bus(Bus::WithReceiveBuffer(globals.lcm_url, 8 << 20));
  const Channels channels(globals.prefix);
  gateway::ServeOptions serve = options;
  serve.command_timeout = globals.timeout;
  serve.signer = globals.signer;
  return gateway::Serve(bus, channels, serve);
}

}  // namespace flagsim
