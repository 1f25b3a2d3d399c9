// A finished recording's exports: made one after another off the gateway's loop, each under a
// .part name until whole, so that only a finished file is ever offered; a failed one says why
// and leaves nothing behind.
#include "client/gateway/recording_exports.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

namespace flagsim::gateway {
namespace {

namespace fs = std::filesystem;

/// Polls `done` for at most 10 s of wall time: the exports run on their own thread.
template <class Done>
bool Eventually(const Done& done) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!done() && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  return done();
}

TEST(RecordingExports, EachFormatIsOfferedOnlyOnceWhole) {
  const fs::path directory = fs::path(::testing::TempDir()) / ("exports_" + std::to_string(getpid()));
  fs::create_directories(directory);
  const std::string log = (directory / "session.lcmlog").string();
  std::ofstream(log) << "a log";
  std::atomic<bool> release{false};
  std::vector<std::string> seen_outputs;
  RecordingExports exports({
      {"mcap",
       [&](const std::string& from, const std::string& output, const std::atomic<bool>&) {
         seen_outputs.push_back(output);
         std::ofstream(output) << "from " << from;
         while (!release.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
         return std::string();
       }},
      {"mp4", [](const std::string&, const std::string&,
                 const std::atomic<bool>&) { return std::string("no ffmpeg"); }},
  });
  EXPECT_EQ(exports.State("session.lcmlog"), nlohmann::json::object());
  exports.Begin(log);
  ASSERT_TRUE(Eventually([&] { return exports.State("session.lcmlog")["mcap"]["state"] == "making"; }));
  EXPECT_EQ(exports.State("session.lcmlog")["mp4"]["state"], "waiting");
  EXPECT_FALSE(exports.Ready("session.mcap")) << "not offered while it is being written";
  EXPECT_FALSE(fs::exists(directory / "session.mcap"));
  release = true;
  ASSERT_TRUE(Eventually([&] { return exports.State("session.lcmlog")["mp4"]["state"] == "failed"; }));
  const nlohmann::json state = exports.State("session.lcmlog");
  EXPECT_EQ(state["mcap"]["state"], "ready");
  EXPECT_EQ(state["mcap"]["url"], "/recordings/session.mcap");
  EXPECT_TRUE(exports.Ready("session.mcap"));
  EXPECT_TRUE(fs::exists(directory / "session.mcap"));
  ASSERT_EQ(seen_outputs.size(), 1u);
  EXPECT_NE(seen_outputs[0], (directory / "session.mcap").string()) << "written under another name first";
  EXPECT_EQ(state["mp4"]["error"], "no ffmpeg");
  EXPECT_EQ(state["mp4"]["url"], "");
  EXPECT_FALSE(exports.Ready("session.mp4"));
  EXPECT_FALSE(fs::exists(directory / "session.mp4"));
  fs::remove_all(directory);
}

TEST(RecordingExports, NamesFollowTheLog) {
  EXPECT_EQ(ExportName("flagsim-20261127-101500.lcmlog", "mcap"), "flagsim-20261127-101500.mcap");
  EXPECT_EQ(ExportName("plain", "mp4"), "plain.mp4");
}

}  // namespace
}  // namespace flagsim::gateway
