// Channel names: a prefix and a name, and the prefixes that make valid LCM channel names.
#include "messages/channels.hpp"

#include <gtest/gtest.h>

namespace flagsim {
namespace {

TEST(Channels, NamesArePrefixed) {
  const Channels channels("LAB_");
  EXPECT_EQ(channels.wind, "LAB_WIND");
  EXPECT_EQ(channels.Unprefixed(channels.checkpoint), "CHECKPOINT");
  EXPECT_EQ(channels.AllChannels(), "LAB_.*");
}

TEST(Channels, APrefixIsLettersDigitsAndUnderscores) {
  EXPECT_EQ(Channels::CheckPrefix(Channels::kDefaultPrefix), "");
  EXPECT_EQ(Channels::CheckPrefix("lab_2"), "");
  const std::string longest(Channels::kMaxPrefixLength, 'P');
  EXPECT_EQ(Channels::CheckPrefix(longest), "");
  EXPECT_LE(Channels(longest).design_file.size(), 63u);  // LCM_MAX_CHANNEL_NAME_LENGTH
  EXPECT_EQ(Channels::CheckPrefix(""), "'' is 0 characters; allowed 1 .. 52 letters, digits and '_'");
  EXPECT_EQ(Channels::CheckPrefix(longest + "P"),
            "'" + longest + "P' is 53 characters; allowed 1 .. 52 letters, digits and '_'");
  EXPECT_EQ(Channels::CheckPrefix("my-prefix"),
            "'my-prefix' is not a channel prefix; allowed 1 .. 52 letters, digits and '_'");
  for (const std::string bad : {"A.B", "A B", "A*", "A/B", "\xc3\xbc", "A\x1b"})
    EXPECT_NE(Channels::CheckPrefix(bad).find("is not a channel prefix"), std::string::npos) << bad;
  EXPECT_EQ(Channels::CheckPrefix("A\x1b"),
            "'A\\x1b' is not a channel prefix; allowed 1 .. 52 letters, digits and '_'");
}

// A replica's own prefix: the default one, six hex digits and '_'; two draws differ (24 random
// bits: they coincide once in 16.7 million runs).
TEST(Channels, ARandomPrefixIsAValidOneOfItsOwn) {
  const std::string first = Channels::RandomPrefix(), second = Channels::RandomPrefix();
  EXPECT_EQ(Channels::CheckPrefix(first), "");
  EXPECT_EQ(first.size(), std::string(Channels::kDefaultPrefix).size() + 7);
  EXPECT_EQ(first.rfind(Channels::kDefaultPrefix, 0), 0u);
  EXPECT_EQ(first.back(), '_');
  EXPECT_EQ(first.find_first_not_of("0123456789ABCDEF", 8), first.size() - 1) << first;
  EXPECT_NE(first, second);
}

}  // namespace
}  // namespace flagsim
