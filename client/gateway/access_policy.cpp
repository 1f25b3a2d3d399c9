#include "client/gateway/access_policy.hpp"

#include <algorithm>
#include <cctype>
#include <random>

namespace flagsim::gateway {
namespace {

std::string Lower(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  return lower;
}

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string PercentDecoded(std::string_view text) {
  std::string decoded;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '%' && i + 2 < text.size() && HexValue(text[i + 1]) >= 0 && HexValue(text[i + 2]) >= 0) {
      decoded += static_cast<char>(HexValue(text[i + 1]) * 16 + HexValue(text[i + 2]));
      i += 2;
    } else {
      decoded += text[i] == '+' ? ' ' : text[i];
    }
  }
  return decoded;
}

/// "host:port" -> "host"; "[::1]:port" -> "::1".
std::string_view HostWithoutPort(std::string_view host) {
  if (!host.empty() && host.front() == '[') {
    const size_t close = host.find(']');
    return close == std::string_view::npos ? host : host.substr(1, close - 1);
  }
  const size_t colon = host.find(':');
  return colon == std::string_view::npos ? host : host.substr(0, colon);
}

/// The cookie `name`'s value in a Cookie header ("a=1; flagsim_token=T"), "" if absent.
std::string CookieValue(std::string_view header, std::string_view name) {
  size_t start = 0;
  while (start < header.size()) {
    size_t end = header.find(';', start);
    if (end == std::string_view::npos) end = header.size();
    std::string_view pair = header.substr(start, end - start);
    while (!pair.empty() && pair.front() == ' ') pair.remove_prefix(1);
    if (pair.size() > name.size() && pair.substr(0, name.size()) == name && pair[name.size()] == '=') {
      return std::string(pair.substr(name.size() + 1));
    }
    start = end + 1;
  }
  return "";
}

/// The token a request presents, and whether it came in the query.
std::string PresentedToken(const RequestCredentials& request, bool* in_query) {
  std::string token = QueryParameter(request.target, "token");
  *in_query = !token.empty();
  if (!token.empty()) return token;
  constexpr std::string_view kBearer = "Bearer ";
  if (request.authorization.substr(0, kBearer.size()) == kBearer) {
    return std::string(request.authorization.substr(kBearer.size()));
  }
  return CookieValue(request.cookie, "flagsim_token");
}

/// Same origin: the Origin's host and port are the Host the request was sent to.
bool SameOrigin(std::string_view origin, std::string_view host) {
  const size_t scheme = origin.find("://");
  if (scheme == std::string_view::npos) return false;
  return Lower(origin.substr(scheme + 3)) == Lower(host);
}

}  // namespace

std::string_view TargetPath(std::string_view target) { return target.substr(0, target.find('?')); }

std::string QueryParameter(std::string_view target, std::string_view name) {
  const size_t question = target.find('?');
  if (question == std::string_view::npos) return "";
  std::string_view query = target.substr(question + 1);
  while (!query.empty()) {
    const size_t amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    const size_t equals = pair.find('=');
    if (pair.substr(0, equals) == name) {
      return equals == std::string_view::npos ? "" : PercentDecoded(pair.substr(equals + 1));
    }
    if (amp == std::string_view::npos) break;
    query.remove_prefix(amp + 1);
  }
  return "";
}

bool IsLoopbackHost(std::string_view host) {
  const std::string name = Lower(host);
  return name == "localhost" || name == "::1" || name.rfind("127.", 0) == 0 || name == "localhost.";
}

bool SameSecret(std::string_view a, std::string_view b) {
  if (a.size() != b.size() || b.empty()) return false;  // a token's length is no secret
  unsigned char difference = 0;
  for (size_t i = 0; i < a.size(); ++i) difference |= static_cast<unsigned char>(a[i] ^ b[i]);
  return difference == 0;
}

std::string NewToken() {
  std::random_device entropy;
  static const char kHex[] = "0123456789abcdef";
  std::string token;
  for (int i = 0; i < 4; ++i) {
    const uint32_t word = entropy();
    for (int nibble = 0; nibble < 8; ++nibble) token += kHex[(word >> (4 * nibble)) & 15];
  }
  return token;
}

AccessDecision CheckAccess(const AccessPolicy& policy, const RequestCredentials& request) {
  AccessDecision decision;
  if (!policy.token.empty()) {
    const std::string presented = PresentedToken(request, &decision.token_in_query);
    if (!SameSecret(presented, policy.token)) {
      return {401, presented.empty() ? "a token is required (?token=, a bearer header or the page's cookie)"
                                     : "the token is wrong"};
    }
  } else if (policy.loopback && !IsLoopbackHost(HostWithoutPort(request.host))) {
    return {403,
            "Host '" + std::string(request.host) + "' is not a loopback name; this gateway serves loopback"};
  }
  if (!request.origin.empty() && !SameOrigin(request.origin, request.host)) {
    const auto& allowed = policy.allow_origins;
    if (std::find(allowed.begin(), allowed.end(), "*") == allowed.end() &&
        std::find(allowed.begin(), allowed.end(), std::string(request.origin)) == allowed.end()) {
      return {403, "Origin '" + std::string(request.origin) + "' is not allowed (see --allow-origin)"};
    }
  }
  return decision;
}

}  // namespace flagsim::gateway
