// One HTTP connection to the gateway (Boost.Beast): requests are read with bounded headers and
// bodies, routed (http_routing.hpp: their token, Host and Origin, method and path), and answered
// with the page, a finished recording, or an error; a WebSocket upgrade is handed to a
// WebSocketSession. Over plain TCP or TLS alike (gateway_streams.hpp): a TLS connection first
// completes its handshake.
#pragma once

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <memory>
#include <optional>

#include "client/gateway/gateway_streams.hpp"
#include "client/gateway/http_routing.hpp"
#include "client/gateway/server_context.hpp"

namespace flagsim::gateway {

template <class Stream>
class HttpSession : public std::enable_shared_from_this<HttpSession<Stream>> {
 public:
  /// `buffer`: bytes already read from the connection (what told TLS from plain HTTP).
  HttpSession(Stream stream, ServerContext& context, boost::beast::flat_buffer buffer = {});
  void Start();

 private:
  using Request = boost::beast::http::request<boost::beast::http::string_body>;

  void OnHandshake(boost::beast::error_code error, size_t bytes_used);
  void Read();
  void OnRead(boost::beast::error_code error, size_t bytes);
  void Upgrade(Request request);
  void Serve(const Request& request, const WebAsset& asset, bool set_cookie);
  void ServeRecording(const Request& request, const HttpRoute& route);
  void Refuse(const Request& request, boost::beast::http::status status, const std::string& reason);
  template <class Body>
  void Send(boost::beast::http::response<Body> response);
  void OnWrite(bool close, boost::beast::error_code error, size_t bytes);

  void Close(boost::asio::ip::tcp::socket::shutdown_type how);

  Stream stream_;
  ServerContext& context_;
  std::string address_;
  boost::beast::flat_buffer buffer_;
  std::optional<boost::beast::http::request_parser<boost::beast::http::string_body>> parser_;
  std::shared_ptr<void> response_;  ///< the response being written
};

}  // namespace flagsim::gateway
