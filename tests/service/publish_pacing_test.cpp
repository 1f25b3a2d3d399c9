#include "server/service/publish_pacing.hpp"

#include <gtest/gtest.h>

namespace flagsim {
namespace {

constexpr double kMessageBurst = PublishPacing::kMessagesPerSecond * PublishPacing::kBurstSeconds;
constexpr double kByteBurst = PublishPacing::kBytesPerSecond * PublishPacing::kBurstSeconds;

TEST(PublishPacing, ABurstLeavesAtOnceAndTheRestAtTheMessageRate) {
  PublishPacing pacing;
  const int burst = static_cast<int>(kMessageBurst);
  for (int i = 0; i < burst; ++i) EXPECT_EQ(pacing.Depart(5.0, 100), 5.0) << i;
  for (int i = 1; i <= 10; ++i) {
    EXPECT_NEAR(pacing.Depart(5.0, 100), 5.0 + i / PublishPacing::kMessagesPerSecond, 1e-12) << i;
  }
}

TEST(PublishPacing, LargeMessagesWaitForTheByteRate) {
  PublishPacing pacing;
  const size_t bytes = static_cast<size_t>(kByteBurst / 2);
  EXPECT_EQ(pacing.Depart(0, bytes), 0);
  EXPECT_EQ(pacing.Depart(0, bytes), 0);  // the bucket is now empty
  EXPECT_NEAR(pacing.Depart(0, bytes), bytes / PublishPacing::kBytesPerSecond, 1e-12);
}

TEST(PublishPacing, AMessageLargerThanTheBucketLeavesOnceItIsFull) {
  PublishPacing pacing;
  EXPECT_EQ(pacing.Depart(0, size_t(3 * kByteBurst)), 0);
  // the bucket is 2 bursts in debt: full again after 3 bursts' time
  EXPECT_NEAR(pacing.Depart(0, size_t(kByteBurst)), 3 * PublishPacing::kBurstSeconds, 1e-12);
}

TEST(PublishPacing, NeverBeforeItIsReadyNorBeforeTheMessageBefore) {
  PublishPacing pacing;
  double last = 0;
  for (int i = 0; i < 200; ++i) {
    const double ready = 0.001 * (i % 7);  // readiness out of order
    const double departure = pacing.Depart(ready, 20000);
    EXPECT_GE(departure, ready);
    EXPECT_GE(departure, last);
    last = departure;
  }
  // idle time refills: a message long after leaves when ready
  EXPECT_EQ(pacing.Depart(last + 1.0, 100), last + 1.0);
}

}  // namespace
}  // namespace flagsim
