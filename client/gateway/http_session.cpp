#include "client/gateway/http_session.hpp"

#include <boost/beast/websocket.hpp>
#include <chrono>

#include "client/gateway/web_assets.hpp"
#include "client/gateway/websocket_session.hpp"

namespace flagsim::gateway {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;

constexpr std::string_view kSubprotocol = "foxglove.websocket.v1";
constexpr std::string_view kRecordings = "/recordings/";

// The page loads only from here; hash-wasm compiles WebAssembly, hence 'wasm-unsafe-eval'.
constexpr const char* kContentSecurityPolicy =
    "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; style-src 'self' 'unsafe-inline'; "
    "img-src 'self' data: blob:; connect-src 'self' ws: wss:";

std::string_view View(beast::string_view text) { return {text.data(), text.size()}; }

std::string_view Header(const http::request<http::string_body>& request, http::field field) {
  const auto found = request.find(field);
  return found == request.end() ? std::string_view() : View(found->value());
}

/// Whether the client offered the Foxglove subprotocol among its Sec-WebSocket-Protocol values.
bool OffersSubprotocol(std::string_view offered) {
  size_t start = 0;
  while (start <= offered.size()) {
    size_t end = offered.find(',', start);
    if (end == std::string_view::npos) end = offered.size();
    std::string_view value = offered.substr(start, end - start);
    while (!value.empty() && value.front() == ' ') value.remove_prefix(1);
    while (!value.empty() && value.back() == ' ') value.remove_suffix(1);
    if (value == kSubprotocol) return true;
    start = end + 1;
  }
  return false;
}

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

// request => access (token, Host, Origin) => upgrade, the page, a recording, or an error
void HttpSession::OnRead(beast::error_code error, size_t) {
  if (error) {  // closed, timed out, or not HTTP within the limits: nothing to answer
    beast::error_code ignored;
    stream_.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
    return;
  }
  Request request = parser_->release();
  const AccessDecision access = CheckAccess(
      context_.access,
      {View(request.target()), Header(request, http::field::host), Header(request, http::field::origin),
       Header(request, http::field::authorization), Header(request, http::field::cookie)});
  if (access.status != 200) {
    ++(access.status == 401 ? context_.gateway.counters().unauthorized
                            : context_.gateway.counters().forbidden);
    return Refuse(request, access.status == 401 ? http::status::unauthorized : http::status::forbidden,
                  access.reason);
  }
  if (websocket::is_upgrade(request)) return Upgrade(std::move(request));
  Serve(request, access.token_in_query);
}

void HttpSession::Upgrade(Request request) {
  if (!OffersSubprotocol(Header(request, http::field::sec_websocket_protocol))) {
    return Refuse(request, http::status::bad_request,
                  "this WebSocket speaks the Foxglove protocol: offer the subprotocol foxglove.websocket.v1");
  }
  if (context_.websocket_clients >= ServerContext::kMaxWebSocketClients) {
    return Refuse(request, http::status::service_unavailable,
                  "already " + std::to_string(ServerContext::kMaxWebSocketClients) + " WebSocket clients");
  }
  std::make_shared<WebSocketSession>(std::move(stream_), context_, address_)->Accept(std::move(request));
}

void HttpSession::Serve(const Request& request, bool set_cookie) {
  if (request.method() != http::verb::get && request.method() != http::verb::head) {
    return Refuse(request, http::status::method_not_allowed, "only GET and HEAD");
  }
  const std::string_view path = TargetPath(View(request.target()));
  if (path.substr(0, kRecordings.size()) == kRecordings)
    return ServeRecording(request, path.substr(kRecordings.size()));
  const WebAsset* asset = FindWebAsset(path);
  if (asset == nullptr) return Refuse(request, http::status::not_found, "no such page: " + std::string(path));
  http::response<http::string_body> response{http::status::ok, request.version()};
  response.set(http::field::content_type, std::string(asset->content_type));
  response.set(http::field::cache_control, "no-cache");
  response.set("Content-Security-Policy", kContentSecurityPolicy);
  response.set("X-Content-Type-Options", "nosniff");
  if (set_cookie && !context_.access.token.empty()) {
    response.set(http::field::set_cookie,
                 "flagsim_token=" + context_.access.token + "; HttpOnly; SameSite=Strict; Path=/");
  }
  if (request.method() == http::verb::get) response.body() = std::string(asset->body);
  response.content_length(asset->body.size());
  response.keep_alive(request.keep_alive());
  Send(std::move(response));
}

void HttpSession::ServeRecording(const Request& request, std::string_view name) {
  const std::optional<std::string> path = context_.gateway.RecordingFile(name);
  if (!path)
    return Refuse(request, http::status::not_found, "no finished recording named " + std::string(name));
  http::file_body::value_type file;
  beast::error_code error;
  file.open(path->c_str(), beast::file_mode::scan, error);
  if (error) return Refuse(request, http::status::not_found, "cannot read " + std::string(name));
  const uint64_t size = file.size();
  http::response<http::file_body> response{std::piecewise_construct, std::make_tuple(std::move(file)),
                                           std::make_tuple(http::status::ok, request.version())};
  response.set(http::field::content_type, "application/octet-stream");
  response.set(http::field::content_disposition, "attachment; filename=\"" + std::string(name) + "\"");
  response.content_length(size);
  response.keep_alive(request.keep_alive());
  if (request.method() == http::verb::head) response.body().close();
  Send(std::move(response));
}

void HttpSession::Refuse(const Request& request, http::status status, const std::string& reason) {
  http::response<http::string_body> response{status, request.version()};
  response.set(http::field::content_type, "text/plain; charset=utf-8");
  if (status == http::status::unauthorized) response.set(http::field::www_authenticate, "Bearer");
  response.body() = reason + "\n";
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
