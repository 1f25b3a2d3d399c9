#include "client/gateway/http_routing.hpp"

#include <boost/beast/websocket/rfc6455.hpp>

namespace flagsim::gateway {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;

constexpr std::string_view kSubprotocol = "foxglove.websocket.v1";
constexpr std::string_view kRecordings = "/recordings/";

std::string_view View(beast::string_view text) { return {text.data(), text.size()}; }

std::string_view Header(const HttpRequest& request, http::field field) {
  const auto found = request.find(field);
  return found == request.end() ? std::string_view() : View(found->value());
}

HttpRoute Refusal(http::status status, std::string reason) {
  HttpRoute route;
  route.status = status;
  route.reason = std::move(reason);
  return route;
}

}  // namespace

bool OffersFoxgloveSubprotocol(std::string_view offered) {
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

// request => access => upgrade, or method and path => a page asset, a recording, or a refusal
HttpRoute RouteRequest(const HttpRequest& request, const ServerContext& context) {
  const AccessDecision access = CheckAccess(
      context.access,
      {View(request.target()), Header(request, http::field::host), Header(request, http::field::origin),
       Header(request, http::field::authorization), Header(request, http::field::cookie)});
  if (access.status != 200) {
    return Refusal(access.status == 401 ? http::status::unauthorized : http::status::forbidden,
                   access.reason);
  }
  if (beast::websocket::is_upgrade(request)) {
    if (!OffersFoxgloveSubprotocol(Header(request, http::field::sec_websocket_protocol))) {
      return Refusal(
          http::status::bad_request,
          "this WebSocket speaks the Foxglove protocol: offer the subprotocol foxglove.websocket.v1");
    }
    if (context.websocket_clients >= ServerContext::kMaxWebSocketClients) {
      return Refusal(http::status::service_unavailable,
                     "already " + std::to_string(ServerContext::kMaxWebSocketClients) + " WebSocket clients");
    }
    HttpRoute route;
    route.kind = HttpRoute::kUpgrade;
    return route;
  }
  if (request.method() != http::verb::get && request.method() != http::verb::head) {
    return Refusal(http::status::method_not_allowed, "only GET and HEAD");
  }
  const std::string_view path = TargetPath(View(request.target()));
  HttpRoute route;
  if (path.substr(0, kRecordings.size()) == kRecordings) {
    route.recording_name = std::string(path.substr(kRecordings.size()));
    const std::optional<std::string> file = context.gateway.RecordingFile(route.recording_name);
    if (!file) return Refusal(http::status::not_found, "no finished recording named " + route.recording_name);
    route.kind = HttpRoute::kRecording;
    route.recording_path = *file;
    return route;
  }
  route.asset = FindWebAsset(path);
  if (route.asset == nullptr) return Refusal(http::status::not_found, "no such page: " + std::string(path));
  route.kind = HttpRoute::kAsset;
  route.set_cookie = access.token_in_query && !context.access.token.empty();
  return route;
}

}  // namespace flagsim::gateway
