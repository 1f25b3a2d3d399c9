// The server's messages as the gateway's JSON: strings from the bus are bytes, and whatever they
// hold reaches clients as valid JSON text.
#include "client/gateway/bus_json.hpp"

#include <gtest/gtest.h>

namespace flagsim::gateway {
namespace {

using nlohmann::json;

TEST(JsonText, BytesThatAreNotUtf8BecomeReplacementCharacters) {
  status_t status{};
  status.command_authentication = "keys \xff\xfe ok";
  const std::string text = JsonText(StatusJson(status));
  const json parsed = json::parse(text, nullptr, false);
  ASSERT_FALSE(parsed.is_discarded()) << text;
  EXPECT_EQ(parsed.dump().find("\xff"), std::string::npos);
  EXPECT_NE(text.find("keys \xEF\xBF\xBD\xEF\xBF\xBD ok"), std::string::npos) << text;  // U+FFFD twice
}

TEST(JsonText, Utf8StaysAsItIs) {
  ack_t ack{};
  ack.reason = "wind: 70 m/s is over 60 m/s \xE2\x80\x94 allowed 0 .. 60";
  EXPECT_NE(JsonText(AckJson(ack)).find(ack.reason), std::string::npos);
}

}  // namespace
}  // namespace flagsim::gateway
