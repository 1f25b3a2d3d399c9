// One WebSocket client of the gateway (Boost.Beast), speaking foxglove.websocket.v1, over plain
// TCP or TLS (gateway_streams.hpp).
//
//   read loop    each message => ClientProtocol (text: JSON ops; binary: calls, publishes)
//   write loop   one write in flight (Beast allows one): when it completes, the protocol says
//                what is next; the gateway's Wake() starts the loop when it is idle
//   drop         a write that does not complete within kWriteTimeout (a client that stopped
//                reading), a control queue that overflows, or any error: the socket is closed
#pragma once

#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <memory>
#include <optional>
#include <string>

#include "client/gateway/client_protocol.hpp"
#include "client/gateway/gateway_streams.hpp"
#include "client/gateway/server_context.hpp"

namespace flagsim::gateway {

template <class Stream>
class WebSocketSession : public std::enable_shared_from_this<WebSocketSession<Stream>>, public GatewayClient {
 public:
  WebSocketSession(Stream stream, ServerContext& context, std::string address);
  ~WebSocketSession() override;

  /// Completes the handshake the HTTP request began, then serves the client.
  void Accept(boost::beast::http::request<boost::beast::http::string_body> request);

  ClientProtocol& protocol() override { return *protocol_; }
  void Wake() override { Write(); }
  std::string address() const override { return address_; }

 private:
  void OnAccept(boost::beast::error_code error);
  void Read();
  void OnRead(boost::beast::error_code error, size_t bytes);
  void Write();
  void OnWrite(boost::beast::error_code error, size_t bytes);
  void Drop(const char* why);

  boost::beast::websocket::stream<Stream> socket_;
  ServerContext& context_;
  std::string address_;
  boost::beast::flat_buffer read_buffer_;
  boost::asio::steady_timer write_deadline_;
  std::optional<ClientProtocol> protocol_;
  Outgoing writing_;  ///< the message in flight, kept alive until its write completes
  bool write_in_flight_ = false;
  bool open_ = false;
  int id_ = 0;
};

}  // namespace flagsim::gateway
