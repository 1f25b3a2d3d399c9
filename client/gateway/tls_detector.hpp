// A new connection to a gateway that serves TLS: its first bytes say whether it is a TLS
// handshake (then an HttpSession over TLS takes it, with those bytes) or plain HTTP, which gets
// a clear refusal naming the https:// address to open instead; the token is never read in clear.
#pragma once

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <memory>
#include <string>

#include "client/gateway/server_context.hpp"

namespace flagsim::gateway {

class TlsDetector : public std::enable_shared_from_this<TlsDetector> {
 public:
  TlsDetector(boost::asio::ip::tcp::socket socket, ServerContext& context);
  void Start();

 private:
  void OnDetect(boost::beast::error_code error, bool tls);
  void RefusePlainHttp();

  boost::beast::tcp_stream stream_;
  ServerContext& context_;
  boost::beast::flat_buffer buffer_;
  std::string refusal_;  ///< the plain-HTTP answer being written
};

}  // namespace flagsim::gateway
