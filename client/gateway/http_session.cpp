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

HttpSession::HttpSession(boost::asio::ip::tcp::socket socket, ServerContext& context)
    : stream_(std::move(socket)), context_(context) {
  beast::error_code error;
  const auto endpoint = stream_.socket().remote_endpoint(error);
  if (!error) address_ = endpoint.address().to_string() + ":" + std::to_string(endpoint.port());
}

void HttpSession::Read() {
  parser_.emplace();
  parser_->header_limit(ServerContext::kMaxHeaderBytes);
  parser_->body_limit(ServerContext::kMaxHeaderBytes);
  stream_.expires_after(std::chrono::seconds(static_cast<int>(ServerContext::kHttpTimeout)));
  http::async_read(stream_, buffer_, *parser_,
                   beast::bind_front_handler(&HttpSession::OnRead, shared_from_this()));
}

// request => its route (http_routing.hpp) => upgrade, the page, a recording, or a refusal
void HttpSession::OnRead(beast::error_code error, size_t) {
  if (error) {  // closed, timed out, or not HTTP within the limits: nothing to answer
    beast::error_code ignored;
    stream_.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
    return;
  }
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

void HttpSession::Upgrade(Request request) {
  std::make_shared<WebSocketSession>(std::move(stream_), context_, address_)->Accept(std::move(request));
}

void HttpSession::Serve(const Request& request, const WebAsset& asset, bool set_cookie) {
  http::response<http::string_body> response{http::status::ok, request.version()};
  response.set(http::field::content_type, std::string(asset.content_type));
  response.set(http::field::cache_control, "no-cache");
  response.set("Content-Security-Policy", kContentSecurityPolicy);
  response.set("X-Content-Type-Options", "nosniff");
  if (set_cookie) {
    response.set(http::field::set_cookie,
                 "flagsim_token=" + context_.access.token + "; HttpOnly; SameSite=Strict; Path=/");
  }
  if (request.method() == http::verb::get) response.body() = std::string(asset.body);
  response.content_length(asset.body.size());
  response.keep_alive(request.keep_alive());
  Send(std::move(response));
}

void HttpSession::ServeRecording(const Request& request, const HttpRoute& route) {
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

void HttpSession::Refuse(const Request& request, http::status status, const std::string& reason) {
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

template <class Body>
void HttpSession::Send(http::response<Body> response) {
  auto owned = std::make_shared<http::response<Body>>(std::move(response));
  response_ = owned;
  const bool close = owned->need_eof();
  stream_.expires_after(std::chrono::seconds(static_cast<int>(ServerContext::kHttpTimeout)));
  http::async_write(stream_, *owned,
                    beast::bind_front_handler(&HttpSession::OnWrite, shared_from_this(), close));
}

void HttpSession::OnWrite(bool close, beast::error_code error, size_t) {
  response_.reset();
  if (error || close) {
    beast::error_code ignored;
    stream_.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_send, ignored);
    return;
  }
  Read();
}

}  // namespace flagsim::gateway
