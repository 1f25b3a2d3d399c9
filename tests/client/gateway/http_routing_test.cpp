// What the gateway answers each kind of HTTP request, decided without a socket: the page and its
// assets, refusals by access, the WebSocket upgrade and its subprotocol, methods, unknown paths
// and finished recordings by name.
#include "client/gateway/http_routing.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "messages/bus.hpp"
#include "messages/channels.hpp"

namespace flagsim::gateway {
namespace {

namespace http = boost::beast::http;

class HttpRoutingTest : public ::testing::Test {
 protected:
  HttpRoutingTest()
      : bus_("memq://"),
        gateway_(bus_, ServerSelection::One(channels_.prefix), Options()),
        context_{gateway_, {}, "1", 0, nullptr, ""} {}

  static GatewayOptions Options() {
    GatewayOptions options;
    options.record_directory = ::testing::TempDir() + "/http_routing_test_recordings";
    return options;
  }

  static HttpRequest Get(const std::string& target, const std::string& host = "127.0.0.1:8080") {
    HttpRequest request{http::verb::get, target, 11};
    request.set(http::field::host, host);
    return request;
  }

  static HttpRequest Upgrade(const std::string& subprotocols) {
    HttpRequest request = Get("/");
    request.set(http::field::upgrade, "websocket");
    request.set(http::field::connection, "Upgrade");
    request.set(http::field::sec_websocket_key, "dGhlIHNhbXBsZSBub25jZQ==");
    request.set(http::field::sec_websocket_version, "13");
    if (!subprotocols.empty()) request.set(http::field::sec_websocket_protocol, subprotocols);
    return request;
  }

  Bus bus_;
  Channels channels_;
  Gateway gateway_;
  ServerContext context_;
};

TEST_F(HttpRoutingTest, ThePageIsServedAtTheRoot) {
  const HttpRoute route = RouteRequest(Get("/"), context_);
  ASSERT_EQ(route.kind, HttpRoute::kAsset);
  EXPECT_NE(route.asset->content_type.find("text/html"), std::string_view::npos);
  EXPECT_FALSE(route.set_cookie);
}

TEST_F(HttpRoutingTest, AccessRefusalsAreUnauthorizedOrForbidden) {
  EXPECT_EQ(RouteRequest(Get("/", "evil.example"), context_).status, http::status::forbidden);
  context_.access.token = "0123abcd";
  EXPECT_EQ(RouteRequest(Get("/"), context_).status, http::status::unauthorized);
  const HttpRoute with_token = RouteRequest(Get("/?token=0123abcd"), context_);
  EXPECT_EQ(with_token.kind, HttpRoute::kAsset);
  EXPECT_TRUE(with_token.set_cookie) << "the page's own requests carry the token as a cookie";
}

TEST_F(HttpRoutingTest, AWebSocketMustOfferTheFoxgloveSubprotocolAndFindRoom) {
  EXPECT_EQ(RouteRequest(Upgrade("foxglove.websocket.v1"), context_).kind, HttpRoute::kUpgrade);
  EXPECT_EQ(RouteRequest(Upgrade("chat, foxglove.websocket.v1 "), context_).kind, HttpRoute::kUpgrade);
  const HttpRoute none = RouteRequest(Upgrade(""), context_);
  EXPECT_EQ(none.status, http::status::bad_request);
  EXPECT_NE(none.reason.find("foxglove.websocket.v1"), std::string::npos) << none.reason;
  context_.websocket_clients = ServerContext::kMaxWebSocketClients;
  EXPECT_EQ(RouteRequest(Upgrade("foxglove.websocket.v1"), context_).status,
            http::status::service_unavailable);
}

TEST_F(HttpRoutingTest, OnlyGetAndHeadReadPages) {
  HttpRequest post = Get("/");
  post.method(http::verb::post);
  EXPECT_EQ(RouteRequest(post, context_).status, http::status::method_not_allowed);
  HttpRequest head = Get("/");
  head.method(http::verb::head);
  EXPECT_EQ(RouteRequest(head, context_).kind, HttpRoute::kAsset);
}

TEST_F(HttpRoutingTest, UnknownPathsAndRecordingsAreNotFound) {
  const HttpRoute missing = RouteRequest(Get("/nothing.js?x=1"), context_);
  EXPECT_EQ(missing.status, http::status::not_found);
  EXPECT_NE(missing.reason.find("/nothing.js"), std::string::npos) << missing.reason;
  EXPECT_EQ(RouteRequest(Get("/recordings/none.lcmlog"), context_).status, http::status::not_found);
  EXPECT_EQ(RouteRequest(Get("/recordings/../secret.lcmlog"), context_).status, http::status::not_found);
}

TEST_F(HttpRoutingTest, AFinishedRecordingIsServedByItsName) {
  const std::string directory = Options().record_directory;
  std::filesystem::create_directories(directory);
  std::ofstream(directory + "/flagsim-20260101-000000.lcmlog") << "recorded";
  const HttpRoute route = RouteRequest(Get("/recordings/flagsim-20260101-000000.lcmlog"), context_);
  ASSERT_EQ(route.kind, HttpRoute::kRecording);
  EXPECT_EQ(route.recording_name, "flagsim-20260101-000000.lcmlog");
  EXPECT_EQ(route.recording_path, directory + "/flagsim-20260101-000000.lcmlog");
}

}  // namespace
}  // namespace flagsim::gateway
