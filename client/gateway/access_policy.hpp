// Who may use the gateway: the token, the Host and the Origin of each HTTP request and
// WebSocket handshake. Pure functions over header values, so every rule is tested without a
// socket.
//
//   token   when set, required on every request: `?token=T`, `Authorization: Bearer T`, or
//           the cookie flagsim_token=T (set when the page is opened with ?token=T)
//   host    on loopback without a token, Host must name loopback (a DNS-rebinding page at
//           evil.example resolving to 127.0.0.1 sends Host: evil.example and is refused)
//   origin  a browser's Origin must be the gateway itself or one allowed by --allow-origin;
//           programs that send no Origin are not affected
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace flagsim::gateway {

struct AccessPolicy {
  std::string token;                       ///< "" = none required (loopback only)
  bool loopback = true;                    ///< the gateway listens on a loopback address only
  std::vector<std::string> allow_origins;  ///< exact origins ("https://app.foxglove.dev"), or "*"
};

/// What a request carries that access depends on.
struct RequestCredentials {
  std::string_view target;         ///< the request target: path and query
  std::string_view host;           ///< Host header
  std::string_view origin;         ///< Origin header, "" if absent
  std::string_view authorization;  ///< Authorization header
  std::string_view cookie;         ///< Cookie header
};

struct AccessDecision {
  int status = 200;             ///< 200, or 401 (no or wrong token), 403 (origin or host refused)
  std::string reason;           ///< why not, for the response body and the log
  bool token_in_query = false;  ///< the token came as ?token=: worth a cookie for the page's own requests
};

AccessDecision CheckAccess(const AccessPolicy& policy, const RequestCredentials& request);

/// The value of `name` in the query part of `target` ("/x?a=1&token=T" -> "T"), percent-decoded;
/// "" if absent.
std::string QueryParameter(std::string_view target, std::string_view name);

/// The path part of `target`, without the query.
std::string_view TargetPath(std::string_view target);

/// True for the literal addresses and names of loopback: 127.0.0.0/8, ::1, localhost.
bool IsLoopbackHost(std::string_view host);

/// A fresh token: 32 hex digits from the system's random source.
std::string NewToken();

/// Compares in time independent of where the strings differ.
bool SameSecret(std::string_view a, std::string_view b);

}  // namespace flagsim::gateway
