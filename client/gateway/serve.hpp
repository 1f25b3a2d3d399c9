// `flagctl serve`: the gateway's event loop. One thread runs everything: the HTTP and
// WebSocket connections (Boost.Asio; over TLS beyond loopback), the bus (its file descriptor
// watched by the same loop), the gateway's ticks (command resends, its status), and
// SIGINT/SIGTERM, which end it.
#pragma once

#include <boost/asio/ip/tcp.hpp>
#include <functional>
#include <string>
#include <vector>

#include "client/gateway/recording_exports.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"
#include "messages/command_mac.hpp"

namespace flagsim::gateway {

struct ServeOptions {
  std::string listen = "127.0.0.1:8080";  ///< HOST:PORT; port 0 picks a free one
  std::string token;                      ///< "" = none on loopback, generated beyond it
  std::vector<std::string> allow_origins;
  std::string record_directory = "recordings";
  double command_timeout = 2.0;               ///< s to wait for a command's ACK
  CommandSigner signer;                       ///< signs the commands it relays (flagctl --key-file)
  RecordingExports::Exporter video_exporter;  ///< makes each recording's MP4 (flagctl export)
  /// TLS (HTTPS, WSS): with this certificate and key (PEM), on any address; else beyond loopback a
  /// self-signed pair kept in tls_directory, unless plain_http.
  std::string tls_certificate, tls_key;
  std::string tls_directory = "flagsim-tls";
  bool plain_http = false;  ///< beyond loopback without TLS (behind a proxy that adds it)
  /// Several servers (their topics under /PREFIX): these prefixes, or {"all"} for every server
  /// heard; empty: the one server on the globals' prefix, with plain topics.
  std::vector<std::string> servers;
};

/// "HOST:PORT" => the address to listen on: HOST an IP address (a v6 one in brackets too) or
/// localhost, PORT 0 .. 65535 in digits (0: any free one). Throws std::invalid_argument with a
/// message that names the text and what is allowed.
boost::asio::ip::tcp::endpoint ParseListen(const std::string& listen);

/// Serves until a signal. Prints the URLs to open on stdout. Returns 0, or 1 if it cannot
/// listen (the reason on stderr).
int Serve(Bus& bus, const Channels& channels, const ServeOptions& options);

}  // namespace flagsim::gateway
