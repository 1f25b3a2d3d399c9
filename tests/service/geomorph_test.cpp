#include "server/service/geomorph.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "server/service/session.hpp"
#include "server/sim/resample.hpp"

namespace flagsim {
namespace {

/// The breeze after `seconds`, folded: something for a coarser grid to lose.
Session FoldedBreeze(double seconds) {
  Session session{Scene{}};
  while (session.simulation().state().time < seconds) session.Step();
  return session;
}

double LargestGap(const std::vector<float>& x, const std::vector<float>& y, const std::vector<float>& z,
                  const sim::ClothState<float>& state) {
  double largest = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    largest = std::max(largest, double(std::hypot(x[i] - state.x[i], y[i] - state.y[i], z[i] - state.z[i])));
  }
  return largest;
}

// At the switch the picture is the fine flag it left; kSeconds later the coarse flag's own
// surface; between, the detail fades; a later switch of grid ends the blend.
TEST(Geomorph, TheFineFlagFadesIntoTheCoarseOne) {
  Session session = FoldedBreeze(1.5);
  const sim::ClothState<float> fine = session.simulation().state();
  const sim::ClothModel<float> fine_model = session.simulation().model();
  ASSERT_EQ(session.ApplyModel({session.scene().sim.integrator, 10, 16, 12}), "");
  const Geomorph* morph = session.geomorph();
  ASSERT_NE(morph, nullptr);
  EXPECT_EQ(morph->cols(), 32);
  EXPECT_EQ(morph->rows(), 24);
  std::vector<float> x, y, z;
  morph->Draw(session.simulation().model(), session.simulation().state(), &x, &y, &z);
  EXPECT_LT(LargestGap(x, y, z, fine), 1e-5);  // float rounding of R + (fine - R)
  const sim::ClothState<float> coarse_surface =
      sim::Resample(session.simulation().model(), session.simulation().state(), fine_model);
  EXPECT_GT(LargestGap(x, y, z, coarse_surface), 1e-3);  // the wrinkles 16 x 12 cannot hold

  while (session.simulation().state().time < fine.time + Geomorph::kSeconds / 2) session.Step();
  ASSERT_NE(session.geomorph(), nullptr);
  while (session.simulation().state().time < fine.time + Geomorph::kSeconds) session.Step();
  EXPECT_EQ(session.geomorph(), nullptr);
}

TEST(Geomorph, ARefinementNeedsNone) {
  Session session = FoldedBreeze(0.5);
  ASSERT_EQ(session.ApplyModel({session.scene().sim.integrator, 10, 48, 36}), "");
  EXPECT_EQ(session.geomorph(), nullptr);
}

}  // namespace
}  // namespace flagsim
