#include "client/gateway/http_session.hpp"

#include <chrono>

#include "client/gateway/refusal_page.hpp"
#include "client/gateway/websocket_session.hpp"

namespace flagsim::gateway {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;

// The page loads only from here; hash-wasm compiles WebAssembly, hence 'wasm-unsafe-eval'.
constexpr const char* kContentSecurityPolicy =
    "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; style-src 'self' 'unsafe-inline'; "
    "img-src 'self' data: blob:; connect-src 'self' ws: wss:";

}  // namespace

template <class Stream>
HttpSession<Stream>::HttpSession(Stream stream, ServerContext& context, beast::flat_buffer buffer)
    : stream_(std::move(stream)), context_(context), buffer_(std::move(buffer)) {
  beast::error_code error;
  const auto endpoint = beast::get_lowest_layer(stream_).socket().remote_endpoint(error);
  if (!error) address_ = endpoint.address().to_string() + ":" + std::to_string(endpoint.port());
}

// TLS: the handshake (from the bytes already read), then requests; plain: requests at once.
template <class Stream>
void HttpSession<Stream>::Start() {
  if constexpr (kIsTls<Stream>) {
    beast::get_lowest_layer(stream_).expires_after(std::chrono::seconds(int(ServerContext::kHandshakeTimeout)));
    stream_.async_handshake(boost::asio::ssl::stream_base::server, buffer_.data(),
                            beast::bind_front_handler(&HttpSession::OnHandshake, this->shared_from_this()));
  } else {
    Read();
  }
}

template <class Stream>
void HttpSession<Stream>::OnHandshake(beast::error_code error, size_t bytes_used) {
  if (error) return Close(boost::asio::ip::tcp::socket::shutdown_both);  // not TLS after all, or refused
  buffer_.consume(bytes_used);
  Read();
}

template <class Stream>
void HttpSession<Stream>::Close(boost::asio::ip::tcp::socket::shutdown_type how) {
  beast::error_code ignored;
  beast::get_lowest_layer(stream_).socket().shutdown(how, ignored);
}

template <class Stream>
void HttpSession<Stream>::Read() {
  parser_.emplace();
  parser_->header_limit(ServerContext::kMaxHeaderBytes);
  parser_->body_limit(ServerContext::kMaxHeaderBytes);
  beast::get_lowest_layer(stream_).expires_after(std::chrono::seconds(static_cast<int>(ServerContext::kHttpTimeout)));
  http::async_read(stream_, buffer_, *parser_,
                   beast::bind_front_handler(&HttpSession::OnRead, this->shared_from_this()));
}

// request => its route (http_routing.hpp) => upgrade, the page, a recording, or a refusal
template <class Stream>
void HttpSession<Stream>::OnRead(beast::error_code error, size_t) {
  // closed, timed out, or not HTTP within the limits: nothing to answer
  if (error) return Close(boost::asio::ip::tcp::socket::shutdown_both);
  Request request = parser_->release();
  const HttpRoute route = RouteRequest(request, context_);
  switch (route.kind) {
    case HttpRoute::kUpgrade:
      return Upgrade(std::move(request));
    case HttpRoute::kAsset:
      return Serve(request, *route.asset, route.set_cookie);
    case HttpRoute::kRecording:
      return ServeRecording(request, route);
    case HttpRoute::kRefuse:
      break;
  }
  if (route.status == http::status::unauthorized) ++context_.gateway.counters().unauthorized;
  if (route.status == http::status::forbidden) ++context_.gateway.counters().forbidden;
  Refuse(request, route.status, route.reason);
}

template <class Stream>
void HttpSession<Stream>::Upgrade(Request request) {
  std::make_shared<WebSocketSession<Stream>>(std::move(stream_), context_, address_)->Accept(std::move(request));
}

template <class Stream>
void HttpSession<Stream>::Serve(const Request& request, const WebAsset& asset, bool set_cookie) {
  http::response<http::string_body> response{http::status::ok, request.version()};
  response.set(http::field::content_type, std::string(asset.content_type));
  response.set(http::field::cache_control, "no-cache");
  response.set("Content-Security-Policy", kContentSecurityPolicy);
  response.set("X-Content-Type-Options", "nosniff");
  if (set_cookie) {
    response.set(http::field::set_cookie,
                 "flagsim_token=" + context_.access.token + "; HttpOnly; SameSite=Strict; Path=/" +
                     (kIsTls<Stream> ? "; Secure" : ""));
  }
  if (request.method() == http::verb::get) response.body() = std::string(asset.body);
  response.content_length(asset.body.size());
  response.keep_alive(request.keep_alive());
  Send(std::move(response));
}

template <class Stream>
void HttpSession<Stream>::ServeRecording(const Request& request, const HttpRoute& route) {
  http::file_body::value_type file;
  beast::error_code error;
  file.open(route.recording_path.c_str(), beast::file_mode::scan, error);
  if (error) return Refuse(request, http::status::not_found, "cannot read " + route.recording_name);
  const uint64_t size = file.size();
  http::response<http::file_body> response{std::piecewise_construct, std::make_tuple(std::move(file)),
                                           std::make_tuple(http::status::ok, request.version())};
  response.set(http::field::content_type, "application/octet-stream");
  response.set(http::field::content_disposition, "attachment; filename=\"" + route.recording_name + "\"");
  response.content_length(size);
  response.keep_alive(request.keep_alive());
  if (request.method() == http::verb::head) response.body().close();
  Send(std::move(response));
}

template <class Stream>
void HttpSession<Stream>::Refuse(const Request& request, http::status status, const std::string& reason) {
  http::response<http::string_body> response{status, request.version()};
  if (status == http::status::unauthorized) response.set(http::field::www_authenticate, "Bearer");
  const auto accept = request.find(http::field::accept);
  if (accept != request.end() && WantsHtml(std::string_view(accept->value().data(), accept->value().size()))) {
    response.set(http::field::content_type, "text/html; charset=utf-8");
    response.body() = RefusalHtml(static_cast<int>(status), reason);
  } else {
    response.set(http::field::content_type, "text/plain; charset=utf-8");
    response.body() = reason + "\n";
  }
  response.prepare_payload();
  response.keep_alive(false);
  Send(std::move(response));
}

template <class Stream>
template <class Body>
void HttpSession<Stream>::Send(http::response<Body> response) {
  auto owned = std::make_shared<http::response<Body>>(std::move(response));
  response_ = owned;
  const bool close = owned->need_eof();
  beast::get_lowest_layer(stream_).expires_after(std::chrono::seconds(static_cast<int>(ServerContext::kHttpTimeout)));
  http::async_write(stream_, *owned,
                    beast::bind_front_handler(&HttpSession::OnWrite, this->shared_from_this(), close));
}

template <class Stream>
void HttpSession<Stream>::OnWrite(bool close, beast::error_code error, size_t) {
  response_.reset();
  if (error || close) return Close(boost::asio::ip::tcp::socket::shutdown_send);
  Read();
}

template class HttpSession<PlainStream>;
template class HttpSession<TlsStream>;

}  // namespace flagsim::gateway
