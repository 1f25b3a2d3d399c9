// What every connection of the gateway's server shares: the gateway, who may come in, and the
// limits. One event loop runs them all.
#pragma once

#include <boost/asio/ssl/context.hpp>
#include <string>

#include "client/gateway/access_policy.hpp"
#include "client/gateway/gateway.hpp"

namespace flagsim::gateway {

struct ServerContext {
  static constexpr size_t kMaxHeaderBytes = 8 * 1024;
  static constexpr size_t kMaxClientMessageBytes = 256 * 1024;  ///< a WebSocket message from a client
  static constexpr int kMaxWebSocketClients = 32;
  static constexpr double kWriteTimeout = 10;  ///< s a client may take to read one message
  static constexpr double kHttpTimeout = 30;   ///< s for a request to arrive, or a response to leave
  static constexpr double kHandshakeTimeout = 10;

  Gateway& gateway;
  AccessPolicy access;
  std::string session_id;  ///< serverInfo's: this gateway's run
  int websocket_clients = 0;
  boost::asio::ssl::context* tls = nullptr;  ///< serving HTTPS and WSS when set (tls_certificate.hpp)
  std::string https_hint;                    ///< the https:// address a plain-HTTP request is told to open
};

}  // namespace flagsim::gateway
