// The grid's share of screen_error: how far a grid's flat triangles stand from the smooth cloth
// they sample, on screen.
//
// A smooth surface of curvature k sampled every h and drawn as a piecewise-linear mesh is off by
// at most its sagitta, h^2 k / 8 (a chord of length h under an arc of radius 1 / k). With the
// cloth's curvature k_95 (the 95th percentile over interior nodes of |L x|, bending.hpp: the mean
// curvature normal's length, grid-independent once the cloth converges under refinement) and the
// pixels a metre of cloth covers where it is closest to the eye (the 95th percentile over the
// grid's edges of their projected length per metre of rest length), a grid of spacing h shows
//   resolution_px = h^2 k_95 / 8 * pixels per metre,
// h the larger of the grid's two spacings. Well-posed only because the cloth's own folds, not the
// grid's, set k (docs/physics.md, "The same cloth at every grid").
#pragma once

#include "server/render/camera.hpp"
#include "server/sim/cloth_model.hpp"
#include "server/sim/cloth_state.hpp"

namespace flagsim::model {

/// What a state says about the cloth and its picture, independent of the grid it is on.
struct ClothOnScreen {
  double curvature = 0;         ///< 1/m, the 95th percentile of |L x| over interior nodes
  double pixels_per_metre = 0;  ///< px/m, the 95th percentile over edges
};
template <typename Real>
ClothOnScreen MeasureClothOnScreen(const sim::ClothModel<Real>& model, const sim::ClothState<Real>& state,
                                   const render::Camera& camera);

/// px: the sagitta of a grid of cols x rows nodes over a width x height flag, on screen.
double ResolutionErrorPx(const ClothOnScreen& cloth, double width, double height, int cols, int rows);

}  // namespace flagsim::model
