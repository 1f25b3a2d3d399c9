#include "server/service/log_publisher.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "messages/event_log_reader.hpp"
#include "tests/service/log_fixtures.hpp"

namespace flagsim {
namespace {

using testing::TempPath;

constexpr int64_t kStart = 1700000000000000;  // us since the Unix epoch

std::vector<LogEvent> ReadLog(const std::string& path) {
  EventLogReader reader(path);
  std::vector<LogEvent> events;
  LogEvent event;
  while (reader.Next(&event)) events.push_back(event);
  EXPECT_EQ(reader.end(), EventLogReader::End::kClean) << reader.problem();
  return events;
}

TEST(LogPublisher, StampsEventsWithSimulatedTime) {
  const std::string path = TempPath("stamps.lcmlog");
  {
    LogPublisher log(path, kStart);
    const uint8_t bytes[3] = {1, 2, 3};
    log.Publish("A", bytes, 3);
    log.AdvanceTo(0.25);
    EXPECT_EQ(log.utime(), kStart + 250000);
    log.Publish("B", bytes, 2);
    log.Close();
    EXPECT_EQ(log.events(), 2);
    EXPECT_EQ(log.bytes(), 2 * EventLogReader::kHeaderBytes + 1 + 3 + 1 + 2);
  }
  const std::vector<LogEvent> events = ReadLog(path);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].channel, "A");
  EXPECT_EQ(events[0].timestamp, kStart);
  EXPECT_EQ(events[1].timestamp, kStart + 250000);
  EXPECT_EQ(events[1].data, (std::vector<uint8_t>{1, 2}));
  std::remove(path.c_str());
}

// Paced messages go out as the live server's paced publisher would send them, and the
// messages published meanwhile fall between them, in time order.
TEST(LogPublisher, PacedMessagesInterleaveWithTheOthersInTimeOrder) {
  const std::string path = TempPath("paced.lcmlog");
  const int tiles = 40;
  std::vector<double> expected;  // the pacing's departures, computed alone
  PublishPacing pacing;
  for (int i = 0; i < tiles; ++i) expected.push_back(pacing.Depart(0, 1000));
  {
    LogPublisher log(path, kStart);
    for (int i = 0; i < tiles; ++i) log.Enqueue("TILE", std::vector<uint8_t>(1000, uint8_t(i)));
    const uint8_t state = 9;
    for (int k = 1; k <= 5; ++k) {  // STATE every 2 ms while the tiles go out
      log.AdvanceTo(0.002 * k);
      log.Publish("STATE", &state, 1);
    }
    log.Close();  // the tiles still due
  }
  const std::vector<LogEvent> events = ReadLog(path);
  ASSERT_EQ(events.size(), size_t(tiles + 5));
  int tile = 0, states = 0;
  for (size_t i = 0; i < events.size(); ++i) {
    if (i > 0) {
      EXPECT_GE(events[i].timestamp, events[i - 1].timestamp);
    }
    if (events[i].channel == "TILE") {
      EXPECT_EQ(events[i].data[0], tile) << "in the order queued";
      EXPECT_EQ(events[i].timestamp, kStart + std::llround(expected[tile] * 1e6));
      ++tile;
    } else {
      ++states;
      EXPECT_EQ(events[i].timestamp, kStart + 2000 * states);
    }
  }
  EXPECT_EQ(tile, tiles);
  // the case is worth testing only if the tiles span several STATEs
  EXPECT_GT(expected.back(), 0.004);
  EXPECT_LT(expected.back(), 0.010);
  std::remove(path.c_str());
}

TEST(LogPublisher, AFileThatCannotBeWrittenIsNamed) {
  try {
    LogPublisher log("/nonexistent/x.lcmlog", kStart);
    FAIL() << "no exception";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/x.lcmlog"), std::string::npos);
  }
}

}  // namespace
}  // namespace flagsim
