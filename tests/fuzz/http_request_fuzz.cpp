// Fuzz target: the gateway's HTTP requests (flagctl serve) up to their answer: the bytes parsed
// as its sessions parse them (Boost.Beast's parser with the same header and body limits), then
// routed as they are routed (client/gateway/http_routing.hpp: token, Host, Origin, the
// WebSocket upgrade's subprotocols, method, page assets, recordings by name). The input's first
// byte picks who may come in:
//
//   bit 0  a token is required (as beyond loopback)     bit 1  the gateway listens beyond loopback
//   bit 2  --allow-origin https://app.foxglove.dev     bit 3  the WebSocket clients are all taken
//
// and the rest is the request as it comes down the socket.
#include <unistd.h>

#include <boost/asio/buffer.hpp>
#include <boost/beast/http.hpp>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "client/gateway/gateway.hpp"
#include "client/gateway/http_routing.hpp"
#include "client/gateway/server_context.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "tests/fuzz/command_server.hpp"

using namespace flagsim;
namespace http = boost::beast::http;

namespace {

/// A gateway whose recordings directory holds one finished recording, for /recordings/NAME.
struct Served {
  Served() : bus("memq://"), gateway(bus, gateway::ServerSelection::One(channels.prefix), Options()) {
    std::filesystem::create_directories(Options().record_directory);
    std::ofstream(Options().record_directory + "/flagsim-20260101-000000.lcmlog") << "recorded";
  }
  static gateway::GatewayOptions Options() {
    gateway::GatewayOptions options;
    options.record_directory =
        (std::filesystem::temp_directory_path() / ("flagsim-fuzz-http-" + std::to_string(getpid()))).string();
    return options;
  }
  Bus bus;
  Channels channels;
  gateway::Gateway gateway;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool quiet = (fuzz::QuietLogs(), true);
  (void)quiet;
  static Served served;
  if (size == 0) return 0;
  gateway::ServerContext context{served.gateway, {}, "fuzz", 0, nullptr, ""};
  if (data[0] & 1) context.access.token = "0123456789abcdef0123456789abcdef";
  context.access.loopback = !(data[0] & 2);
  if (data[0] & 4) context.access.allow_origins = {"https://app.foxglove.dev"};
  if (data[0] & 8) context.websocket_clients = gateway::ServerContext::kMaxWebSocketClients;

  http::request_parser<http::string_body> parser;
  parser.header_limit(gateway::ServerContext::kMaxHeaderBytes);
  parser.body_limit(gateway::ServerContext::kMaxHeaderBytes);
  parser.eager(true);
  boost::beast::error_code error;
  size_t used = 1;
  while (used < size && !parser.is_done() && !error) {
    const size_t taken = parser.put(boost::asio::buffer(data + used, size - used), error);
    if (taken == 0) break;
    used += taken;
  }
  if (!parser.is_done() || error) return 0;  // the session closes such a connection unanswered
  gateway::RouteRequest(parser.get(), context);
  return 0;
}
