#include "client/gateway/tls_detector.hpp"

#include <boost/beast/core/detect_ssl.hpp>
#include <chrono>

#include "client/gateway/http_session.hpp"

namespace flagsim::gateway {

namespace beast = boost::beast;

TlsDetector::TlsDetector(boost::asio::ip::tcp::socket socket, ServerContext& context)
    : stream_(std::move(socket)), context_(context) {}

void TlsDetector::Start() {
  stream_.expires_after(std::chrono::seconds(int(ServerContext::kHandshakeTimeout)));
  beast::async_detect_ssl(stream_, buffer_, beast::bind_front_handler(&TlsDetector::OnDetect, shared_from_this()));
}

void TlsDetector::OnDetect(beast::error_code error, bool tls) {
  if (error) return;  // closed or silent: nothing to answer
  if (!tls) return RefusePlainHttp();
  std::make_shared<HttpSession<TlsStream>>(TlsStream(std::move(stream_), *context_.tls), context_, std::move(buffer_))
      ->Start();
}

// Whatever the request was, its answer is a 400 that says to use HTTPS, and the connection ends.
void TlsDetector::RefusePlainHttp() {
  const std::string body = "this gateway speaks HTTPS and WSS only (TLS: the token must not cross the network "
                           "in clear); open " + context_.https_hint + "\n";
  refusal_ = "HTTP/1.1 400 Bad Request\r\nContent-Type: text/plain; charset=utf-8\r\nConnection: close\r\n"
             "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
  boost::asio::async_write(stream_, boost::asio::buffer(refusal_),
                           [self = shared_from_this()](beast::error_code, size_t) {
                             beast::error_code ignored;
                             self->stream_.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
                           });
}

}  // namespace flagsim::gateway
