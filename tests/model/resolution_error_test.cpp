#include "server/model/resolution_error.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "server/render/camera.hpp"

namespace flagsim::model {
namespace {

sim::ClothModel<double> Grid(int cols, int rows) {
  sim::SimParams params;
  params.cols = cols;
  params.rows = rows;
  params.imperfection = 0;
  return sim::BuildClothModel<double>(params);
}

/// The rest grid rolled about a vertical axis onto a cylinder of radius R, as a flag curls.
sim::ClothState<double> Rolled(const sim::ClothModel<double>& model, double R) {
  sim::ClothState<double> state = sim::RestState(model);
  for (int i = 0; i < model.num_nodes(); ++i) {
    const double u = model.rest_x[i];
    state.x[i] = R * std::sin(u / R);
    state.z[i] = R * (1 - std::cos(u / R));
  }
  return state;
}

TEST(ResolutionError, ACylindersCurvatureIsOneOverItsRadiusAtEveryGrid) {
  const render::Camera camera;
  for (const auto& [cols, rows] : {std::pair{16, 12}, std::pair{32, 24}, std::pair{64, 48}}) {
    const sim::ClothModel<double> model = Grid(cols, rows);
    const ClothOnScreen cloth = MeasureClothOnScreen(model, Rolled(model, 0.8), camera);
    EXPECT_NEAR(cloth.curvature, 1 / 0.8, 0.01 / 0.8) << cols << " x " << rows;
  }
}

TEST(ResolutionError, IsTheSagittaOfACellOnScreen) {
  // Rolled onto radius R, a chord of h stands R (1 - cos(h / 2R)) ~ h^2 / (8 R) from the arc;
  // pixels per metre as the camera sees the flag at rest: the head-on camera 4 m away.
  render::Camera camera;
  camera.eye = {0.8, 2.5, 4.0};
  camera.target = {0.8, 2.5, 0.0};
  const sim::ClothModel<double> model = Grid(32, 24);
  const double R = 1.0;
  const ClothOnScreen cloth = MeasureClothOnScreen(model, sim::RestState(model), camera);
  const ClothOnScreen rolled{1 / R, cloth.pixels_per_metre};
  const double h = std::max(model.dx, model.dy);
  const double sagitta = R * (1 - std::cos(h / (2 * R)));
  EXPECT_NEAR(ResolutionErrorPx(rolled, 1.5, 1.0, 32, 24), sagitta * cloth.pixels_per_metre,
              0.01 * sagitta * cloth.pixels_per_metre);
  // 720 px over the 40-degree field of view at 4 m: about 0.5 px per millimetre.
  const double expected = camera.height / (2 * 4.0 * std::tan(camera.fov_y / 2));
  EXPECT_NEAR(cloth.pixels_per_metre, expected, 0.1 * expected);
  // A quarter of the error at twice the resolution.
  EXPECT_NEAR(ResolutionErrorPx(rolled, 1.5, 1.0, 63, 47), ResolutionErrorPx(rolled, 1.5, 1.0, 32, 24) / 4, 1e-12);
}

}  // namespace
}  // namespace flagsim::model
