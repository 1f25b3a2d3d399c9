// One HTTP connection to the gateway (Boost.Beast): requests are read with bounded headers and
// bodies, routed (http_routing.hpp: their token, Host and Origin, method and path), and answered
// with the page, a finished recording, or an error; a WebSocket upgrade is handed to a
// WebSocketSession.
#pragma once

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <memory>
#include <optional>

#include "client/gateway/http_routing.hpp"
#include "client/gateway/server_context.hpp"

namespace flagsim::gateway {

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(boost::asio::ip::tcp::socket socket, ServerContext& context);
  void Start() { Read(); }

 private:
  using Request = boost::beast::http::request<boost::beast::http::string_body>;

  void Read();
  void OnRead(boost::beast::error_code error, size_t bytes);
  void Upgrade(Request request);
  void Serve(const Request& request, const WebAsset& asset, bool set_cookie);
  void ServeRecording(const Request& request, const HttpRoute& route);
  void Refuse(const Request& request, boost::beast::http::status status, const std::string& reason);
  template <class Body>
  void Send(boost::beast::http::response<Body> response);
  void OnWrite(bool close, boost::beast::error_code error, size_t bytes);

  boost::beast::tcp_stream stream_;
  ServerContext& context_;
  std::string address_;
  boost::beast::flat_buffer buffer_;
  std::optional<boost::beast::http::request_parser<boost::beast::http::string_body>> parser_;
  std::shared_ptr<void> response_;  ///< the response being written
};

}  // namespace flagsim::gateway
