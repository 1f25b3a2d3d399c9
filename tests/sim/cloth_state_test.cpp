#include "server/sim/cloth_state.hpp"

#include <gtest/gtest.h>
#include <xxhash.h>

#include <cmath>

namespace flagsim::sim {
namespace {

TEST(StateHash, ChangesWithAnyBitOfPositionOrVelocity) {
  const ClothModel<float> model = BuildClothModel<float>(SimParams{});
  ClothState<float> state = RestState(model);
  const uint64_t rest = StateHash(state);
  EXPECT_EQ(StateHash(RestState(model)), rest);
  state.vz[17] = std::nextafter(0.0f, 1.0f);
  EXPECT_NE(StateHash(state), rest);
  state.vz[17] = 0;
  EXPECT_EQ(StateHash(state), rest);
  state.time = 5;  // the clock is not part of the hash
  EXPECT_EQ(StateHash(state), rest);
}

TEST(StateHash, IsXxh3OfTheArraysInOrder) {
  ClothState<float> state;
  state.x = {1.0f, 2.0f};
  state.y = {3.0f, 4.0f};
  state.z = {5.0f, 6.0f};
  state.vx = {7.0f, 8.0f};
  state.vy = {9.0f, 10.0f};
  state.vz = {11.0f, 12.0f};
  const float bytes[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};  // the arrays back to back
  EXPECT_EQ(StateHash(state), XXH3_64bits(bytes, sizeof(bytes)));
}

TEST(KineticEnergy, IsHalfMassTimesSpeedSquaredOverTheFreeNodes) {
  const ClothModel<float> model = BuildClothModel<float>(SimParams{});
  ClothState<float> state = RestState(model);
  EXPECT_EQ(KineticEnergy(model, state), 0);
  const int free = model.index(1, 3), pinned = model.index(1, 0);
  ASSERT_FALSE(model.pinned(free));
  ASSERT_TRUE(model.pinned(pinned));
  state.vx[free] = 3;
  state.vy[free] = -4;    // 5 m/s
  state.vz[pinned] = 10;  // a pinned node rides the pole: left out
  EXPECT_DOUBLE_EQ(KineticEnergy(model, state), 0.5 * double(model.mass[free]) * 5 * 5);
}

}  // namespace
}  // namespace flagsim::sim
