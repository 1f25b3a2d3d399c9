// What the gateway answers an HTTP request, decided from the request alone (no socket), so that
// every rule is tested and fuzzed without one; http_session.hpp carries the answer out.
//
//   access       the token, Host and Origin (access_policy.hpp)        else 401 or 403
//   upgrade      a WebSocket handshake offering foxglove.websocket.v1  else 400; 503 when full
//   method       GET or HEAD                                           else 405
//   path         /recordings/NAME: a finished recording; a page asset  else 404
#pragma once

#include <boost/beast/http.hpp>
#include <string>
#include <string_view>

#include "client/gateway/server_context.hpp"
#include "client/gateway/web_assets.hpp"

namespace flagsim::gateway {

struct HttpRoute {
  enum Kind { kRefuse, kUpgrade, kAsset, kRecording };
  Kind kind = kRefuse;
  boost::beast::http::status status = boost::beast::http::status::ok;  ///< kRefuse: why, as HTTP says it
  std::string reason;                                                  ///< kRefuse: the response's body
  const WebAsset* asset = nullptr;                                     ///< kAsset
  bool set_cookie = false;     ///< kAsset: the token came as ?token=, so the page's own requests get it
  std::string recording_name;  ///< kRecording: as the path names it
  std::string recording_path;  ///< kRecording: the file
};

using HttpRequest = boost::beast::http::request<boost::beast::http::string_body>;

HttpRoute RouteRequest(const HttpRequest& request, const ServerContext& context);

/// Whether a Sec-WebSocket-Protocol header's comma-separated values offer foxglove.websocket.v1.
bool OffersFoxgloveSubprotocol(std::string_view offered);

}  // namespace flagsim::gateway
