#include "sim/cloth_state.hpp"

#include <gtest/gtest.h>

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

TEST(StateHash, IsFnv1aOfTheArraysInOrder) {
  ClothState<float> state;
  state.x = {1.0f};
  state.y = state.z = state.vx = state.vy = state.vz = {0.0f};
  // FNV-1a 64 over the 24 bytes: 00 00 80 3f, then 20 zero bytes.
  uint64_t expected = 0xcbf29ce484222325ull;
  const unsigned char bytes[4] = {0x00, 0x00, 0x80, 0x3f};
  for (unsigned char b : bytes) expected = (expected ^ b) * 0x100000001b3ull;
  for (int i = 0; i < 20; ++i) expected = (expected ^ 0) * 0x100000001b3ull;
  EXPECT_EQ(StateHash(state), expected);
}

}  // namespace
}  // namespace flagsim::sim
