// Who may use the gateway: the token in each of its three forms, loopback's Host rule against
// DNS rebinding, and the Origin rule against other sites' pages.
#include "client/gateway/access_policy.hpp"

#include <gtest/gtest.h>

namespace flagsim::gateway {
namespace {

RequestCredentials Request(std::string_view target, std::string_view host = "127.0.0.1:8080") {
  RequestCredentials request;
  request.target = target;
  request.host = host;
  return request;
}

TEST(AccessPolicy, WithoutATokenLoopbackNamesAreServed) {
  const AccessPolicy policy;
  for (const char* host : {"127.0.0.1:8080", "localhost:8080", "[::1]:8080", "127.0.0.1"}) {
    EXPECT_EQ(CheckAccess(policy, Request("/", host)).status, 200) << host;
  }
}

TEST(AccessPolicy, WithoutATokenOtherHostNamesAreRefused) {
  const AccessDecision decision = CheckAccess(AccessPolicy{}, Request("/", "evil.example:8080"));
  EXPECT_EQ(decision.status, 403);
  EXPECT_NE(decision.reason.find("evil.example"), std::string::npos) << decision.reason;
}

TEST(AccessPolicy, TheTokenComesInTheQueryABearerHeaderOrTheCookie) {
  AccessPolicy policy;
  policy.token = "0123abcd";
  EXPECT_EQ(CheckAccess(policy, Request("/")).status, 401);
  EXPECT_EQ(CheckAccess(policy, Request("/?token=wrong567")).status, 401);
  EXPECT_EQ(CheckAccess(policy, Request("/?token=0123abc")).status, 401) << "a prefix is not the token";
  const AccessDecision query = CheckAccess(policy, Request("/?a=1&token=0123abcd"));
  EXPECT_EQ(query.status, 200);
  EXPECT_TRUE(query.token_in_query);
  RequestCredentials bearer = Request("/app.js");
  bearer.authorization = "Bearer 0123abcd";
  EXPECT_EQ(CheckAccess(policy, bearer).status, 200);
  RequestCredentials cookie = Request("/app.js");
  cookie.cookie = "theme=dark; flagsim_token=0123abcd";
  const AccessDecision from_cookie = CheckAccess(policy, cookie);
  EXPECT_EQ(from_cookie.status, 200);
  EXPECT_FALSE(from_cookie.token_in_query);
}

TEST(AccessPolicy, WithATokenAnyHostNameIsServed) {
  AccessPolicy policy;
  policy.token = "0123abcd";
  policy.loopback = false;
  EXPECT_EQ(CheckAccess(policy, Request("/?token=0123abcd", "flagbox.lan:8080")).status, 200);
}

TEST(AccessPolicy, BrowsersMustComeFromTheGatewayOrAnAllowedOrigin) {
  AccessPolicy policy;
  RequestCredentials request = Request("/");
  request.origin = "http://127.0.0.1:8080";
  EXPECT_EQ(CheckAccess(policy, request).status, 200) << "the page itself";
  request.origin = "https://evil.example";
  EXPECT_EQ(CheckAccess(policy, request).status, 403);
  policy.allow_origins = {"https://evil.example"};
  EXPECT_EQ(CheckAccess(policy, request).status, 200);
  policy.allow_origins = {"*"};
  request.origin = "https://other.example";
  EXPECT_EQ(CheckAccess(policy, request).status, 200);
}

TEST(AccessPolicy, QueryParametersArePercentDecoded) {
  EXPECT_EQ(QueryParameter("/x?token=a%2Bb%3d&y=2", "token"), "a+b=");
  EXPECT_EQ(QueryParameter("/x?tokens=1&token=2", "token"), "2");
  EXPECT_EQ(QueryParameter("/x?token", "token"), "");
  EXPECT_EQ(QueryParameter("/x", "token"), "");
  EXPECT_EQ(QueryParameter("/x?token=%zz", "token"), "%zz");
  EXPECT_EQ(TargetPath("/recordings/a.lcmlog?token=1"), "/recordings/a.lcmlog");
}

TEST(AccessPolicy, TokensAreFreshAndSecretsCompareWhole) {
  const std::string a = NewToken(), b = NewToken();
  EXPECT_EQ(a.size(), 32u);
  EXPECT_EQ(a.find_first_not_of("0123456789abcdef"), std::string::npos);
  EXPECT_NE(a, b);
  EXPECT_TRUE(SameSecret(a, a));
  EXPECT_FALSE(SameSecret(a, b));
  EXPECT_FALSE(SameSecret("", ""));
  EXPECT_FALSE(SameSecret(a.substr(0, 31), a));
}

}  // namespace
}  // namespace flagsim::gateway
