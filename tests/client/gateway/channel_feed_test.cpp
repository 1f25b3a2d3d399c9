// A channel's feed: latest wins for a slow reader, lazily made payloads are made once, and a
// deeper feed (the ACKs) gives a reader every message it kept.
#include "client/gateway/channel_feed.hpp"

#include <gtest/gtest.h>

namespace flagsim::gateway {
namespace {

TEST(ChannelFeed, AReaderGetsTheNewestItHasNotHad) {
  ChannelFeed feed;
  EXPECT_EQ(feed.Next(0), nullptr);
  feed.Publish(10, "a");
  feed.Publish(20, "b");
  const FeedMessage* message = feed.Next(0);
  ASSERT_NE(message, nullptr);
  EXPECT_EQ(*message->payload, "b");
  EXPECT_EQ(message->number, 2u);
  EXPECT_EQ(message->timestamp_ns, 20u);
  EXPECT_EQ(feed.Next(message->number), nullptr);
  EXPECT_EQ(feed.newest(), 2u);
}

TEST(ChannelFeed, LazyPayloadsAreMadeOnceAndOnlyWhenTaken) {
  ChannelFeed feed;
  int made = 0;
  feed.PublishLazily(1, [&made] { return std::to_string(++made); });
  feed.PublishLazily(2, [&made] { return std::to_string(++made); });
  EXPECT_EQ(made, 0);
  EXPECT_EQ(*feed.Next(0)->payload, "1") << "the first one was dropped unmade: only the newest is made";
  EXPECT_EQ(*feed.Next(0)->payload, "1");
  EXPECT_EQ(made, 1);
}

TEST(ChannelFeed, ADeeperFeedHandsOutEveryKeptMessageInOrder) {
  ChannelFeed feed(3);
  for (const char* payload : {"a", "b", "c", "d"}) feed.Publish(0, payload);
  std::string read;
  for (uint64_t after = 0; const FeedMessage* message = feed.Next(after); after = message->number) {
    read += *message->payload;
  }
  EXPECT_EQ(read, "bcd");
}

}  // namespace
}  // namespace flagsim::gateway
