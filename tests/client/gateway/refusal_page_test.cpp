// A browser refused for want of a token gets a page that says where the token is; the reason is
// escaped, and other clients keep plain text (WantsHtml).
#include "client/gateway/refusal_page.hpp"

#include <gtest/gtest.h>

namespace flagsim::gateway {
namespace {

TEST(RefusalPage, ABrowserIsToldWhereTheTokenIs) {
  const std::string page = RefusalHtml(401, "the token is wrong");
  EXPECT_NE(page.find("401: the token is wrong"), std::string::npos);
  EXPECT_NE(page.find("<input name=\"token\""), std::string::npos) << "a form to give the token in";
  EXPECT_NE(page.find("?token="), std::string::npos) << "the address flagctl serve printed";
  EXPECT_NE(page.find("scripts/live.sh"), std::string::npos);
}

TEST(RefusalPage, TheReasonIsEscaped) {
  const std::string page = RefusalHtml(403, "Host '<script>' is not a loopback name");
  EXPECT_EQ(page.find("<script>"), std::string::npos);
  EXPECT_NE(page.find("Host &#39;&lt;script&gt;&#39;"), std::string::npos);
  EXPECT_NE(page.find("--listen 0.0.0.0:PORT"), std::string::npos) << "what to do about a loopback gateway";
}

TEST(RefusalPage, OnlyABrowserAsksForHtml) {
  EXPECT_TRUE(WantsHtml("text/html,application/xhtml+xml,application/xml;q=0.9,*/*;q=0.8"));
  EXPECT_FALSE(WantsHtml("*/*"));
  EXPECT_FALSE(WantsHtml(""));
}

}  // namespace
}  // namespace flagsim::gateway
