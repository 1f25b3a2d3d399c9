// flagctl serve's --listen: an address and a port, read whole and strictly.
#include "client/gateway/serve.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace flagsim::gateway {
namespace {

/// The message ParseListen throws for `listen`; "" if it takes it.
std::string Refusal(const std::string& listen) {
  try {
    ParseListen(listen);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(ParseListen, TakesAnAddressOrLocalhostAndAPort) {
  EXPECT_EQ(ParseListen("127.0.0.1:8080"),
            boost::asio::ip::tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), 8080));
  EXPECT_EQ(ParseListen("localhost:0").port(), 0);  // any free one
  EXPECT_EQ(ParseListen("0.0.0.0:65535").port(), 65535);
  EXPECT_TRUE(ParseListen("[::1]:80").address().is_v6());
}

TEST(ParseListen, ThePortIsReadWholeInDigits) {
  EXPECT_EQ(
      Refusal("127.0.0.1:80x"),
      "--listen 127.0.0.1:80x: the port '80x' is not one; allowed 0 .. 65535 in digits (0: any free port)");
  for (const std::string port : {"", "65536", "99999", "-1", "+80", " 80", "80 ", "0x50", "8e1", "123456"}) {
    EXPECT_NE(Refusal("127.0.0.1:" + port).find("the port '" + port + "' is not one; allowed 0 .. 65535"),
              std::string::npos)
        << port;
  }
}

TEST(ParseListen, AHostOrAColonMissingIsNamed) {
  EXPECT_EQ(Refusal("bogus"), "--listen bogus: expected HOST:PORT");
  EXPECT_EQ(Refusal("nosuch:80"), "--listen nosuch:80: 'nosuch' is not an IP address or localhost");
}

}  // namespace
}  // namespace flagsim::gateway
