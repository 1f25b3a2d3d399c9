#include "sim/wind_field.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flagsim::sim {
namespace {

TEST(WindField, RampsLinearlyInSimulatedTime) {
  WindField wind(WindSettings{{2, 0, 0}, 0, 0});
  wind.Set(WindSettings{{6, 0, 4}, 0, 2.0}, 10.0);
  EXPECT_DOUBLE_EQ(wind.Mean(10.0)[0], 2.0);
  EXPECT_DOUBLE_EQ(wind.Mean(11.0)[0], 4.0);
  EXPECT_DOUBLE_EQ(wind.Mean(11.0)[2], 2.0);
  EXPECT_DOUBLE_EQ(wind.Mean(12.0)[0], 6.0);
  EXPECT_DOUBLE_EQ(wind.Mean(99.0)[0], 6.0);
}

TEST(WindField, ANewSettingMidRampStartsFromWhereTheWindIs) {
  WindField wind(WindSettings{{0, 0, 0}, 0, 0});
  wind.Set(WindSettings{{10, 0, 0}, 0, 10.0}, 0.0);
  wind.Set(WindSettings{{0, 0, 0}, 0, 1.0}, 5.0);  // at t = 5 the wind is 5 m/s
  EXPECT_DOUBLE_EQ(wind.Mean(5.0)[0], 5.0);
  EXPECT_DOUBLE_EQ(wind.Mean(5.5)[0], 2.5);
}

TEST(WindField, GustsAreBoundedSmoothAndSeeded) {
  const WindSettings settings{{5, 0, 0}, 0.4, 0};
  const WindField a(settings, 11), b(settings, 11), c(settings, 12);
  double largest = 0, largest_jump = 0;
  bool seeds_differ = false;
  Vec3 previous = a.At(0, 0.3);
  for (int i = 1; i <= 20000; ++i) {
    const double t = i * 1e-3;
    const Vec3 w = a.At(t, 0.3);
    EXPECT_EQ(w, b.At(t, 0.3));
    seeds_differ |= w != c.At(t, 0.3);
    for (int k = 0; k < 3; ++k) {
      largest = std::max(largest, std::abs(w[k] - settings.velocity[k]));
      largest_jump = std::max(largest_jump, std::abs(w[k] - previous[k]));
    }
    previous = w;
  }
  EXPECT_LE(largest, 0.4 * 5 + 1e-12);
  EXPECT_GT(largest, 0.5);  // gusts do happen
  // |dN/du| <= 15/8 for the quintic blend of values in [-1, 1]; du = |w| dt / L per ms
  EXPECT_LE(largest_jump, 0.4 * 5 * 2 * 1.875 * 5 * 1e-3 / WindField::kGustLength);
  EXPECT_TRUE(seeds_differ);
}

TEST(ValueNoise, IsContinuousAcrossLatticePoints) {
  for (int i = -3; i < 3; ++i) {
    EXPECT_NEAR(ValueNoise(5, i - 1e-9), ValueNoise(5, i + 1e-9), 1e-7);
  }
}

}  // namespace
}  // namespace flagsim::sim
