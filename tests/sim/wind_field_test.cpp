#include "server/sim/wind_field.hpp"

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

TEST(WindField, CarriesTheTurbulenceByTheIntegralOfItsSpeed) {
  WindField wind(WindSettings{{3, 0, 4}, 0.2, 0});  // 5 m/s
  EXPECT_DOUBLE_EQ(wind.Carried(2), 10);
  wind.Set(WindSettings{{0, 0, 9}, 0.2, 4}, 2);  // ramps to 9 m/s over 4 s: 28 m more by then
  EXPECT_DOUBLE_EQ(wind.Carried(2), 10);
  EXPECT_DOUBLE_EQ(wind.Carried(4), 10 + 2 * 5 + 4 * (2 * 2 / 8.0));
  EXPECT_DOUBLE_EQ(wind.Carried(6), 10 + 28);
  EXPECT_DOUBLE_EQ(wind.Carried(7), 10 + 28 + 9);
}

// A wind set anew at every 2 ms step, strengthening from 6 to 12 m/s over 8 s, late in a
// session (t = 1000 s): the gusts change as smoothly as in a steady wind. Were the noise
// carried |w| t, each step's 1.5 mm/s more would move it 1 m = 0.7 gust lengths at once.
TEST(WindField, GustsStaySmoothWhenTheWindIsSetEveryStep) {
  const double dt = 0.002, start = 1000;
  WindField wind(WindSettings{{6, 0, 0}, 0.3, 0});
  double largest_jump = 0;
  Vec3 previous = wind.At(start, 0.3);
  for (int i = 1; i <= 4000; ++i) {
    const double t = start + i * dt;
    wind.Set(WindSettings{{6 + 6 * i / 4000.0, 0, 0}, 0.3, 0}, t);
    const Vec3 w = wind.At(t, 0.3);
    largest_jump = std::max(largest_jump, std::abs(w[0] - previous[0]));
    previous = w;
  }
  // The steady bound at the strongest wind, as above, plus the change per step of the mean and
  // of the gusts' amplitude (0.3 of it).
  EXPECT_LE(largest_jump, 0.3 * 12 * 2 * 1.875 * 12 * dt / WindField::kGustLength + 1.3 * 6 / 4000.0);
}

TEST(NoiseCursor, IsContinuousAcrossLatticePoints) {
  NoiseCursor noise(5);
  for (int i = -3; i < 3; ++i) EXPECT_NEAR(noise(i - 1e-9), noise(i + 1e-9), 1e-7);
}

// A checkpoint from outside can carry a wind state whose gust coordinate is astronomically far,
// or not a number: the noise stays defined (no cell index out of int64_t's range).
TEST(NoiseCursor, AnyUHasANoiseValue) {
  NoiseCursor noise(5);
  for (const double u : {1e300, -1e300, 0x1p62, -0x1p63, 0x1p52 + 3}) {
    const double value = noise(u);
    EXPECT_TRUE(value >= -1 && value <= 1) << "u = " << u;
  }
  EXPECT_EQ(noise(0x1p53 + 6), NoiseCursor(5)(6.0)) << "periodic over 2^52 cells";
  EXPECT_EQ(noise(std::nan("")), 0);
  EXPECT_EQ(noise(INFINITY), 0);
}

TEST(NoiseCursor, KeptLatticeValuesGiveWhatFreshOnesGive) {
  NoiseCursor kept(5);
  // Forwards, backwards, within a cell and across several.
  for (const double u : {0.1, 0.4, 0.9, 1.2, 0.7, -2.5, -2.4, 3.0, 2.999, 7.5}) {
    EXPECT_EQ(kept(u), NoiseCursor(5)(u)) << "u = " << u;
  }
}

TEST(WindField, AlongTheFlagIsAtAtEachPointBitForBit) {
  WindField wind(WindSettings{{6, 0, 1.5}, 0.2, 0}, 3);
  wind.Set(WindSettings{{8, 1, -2}, 0.4, 0.5}, 1.0);  // mid-ramp below: the mean and gusts move
  std::vector<double> s(40);
  for (size_t c = 0; c < s.size(); ++c) s[c] = (c + 0.5) * (1.5 / 40);
  for (const double t : {0.0, 1.2, 9.7}) {
    std::vector<Vec3> along(s.size());
    wind.Along(t, s.data(), int(s.size()), along.data());
    for (size_t c = 0; c < s.size(); ++c)
      EXPECT_EQ(along[c], wind.At(t, s[c])) << "t = " << t << ", c = " << c;
  }
}

}  // namespace
}  // namespace flagsim::sim
