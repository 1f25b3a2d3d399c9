// A coarsening the viewer does not see jump: for kSeconds of simulated time after the grid is
// coarsened, frames draw the finer grid it left, the coarse flag's surface carrying the wrinkles
// the coarse grid cannot hold, faded out (a geomorph, as Hoppe's progressive meshes blend a
// level of detail in):
//
//   drawn(t) = R(coarse(t)) + w(t) D,    D = fine(t0) - R(coarse(t0)),
//   w(t) = 1 - s^2 (3 - 2 s),  s = (t - t0) / kSeconds
//
// R resamples the coarse grid onto the fine one over the cloth's (u, v) (sim/resample.hpp), so
// at t0 the picture is the fine flag exactly and at t0 + kSeconds the coarse one's surface. A
// refinement needs none: the fine grid starts on the coarse grid's surface (Simulation::Regrid).
#pragma once

#include <vector>

#include "server/sim/cloth_model.hpp"
#include "server/sim/cloth_state.hpp"
#include "server/sim/node_vectors.hpp"

namespace flagsim {

class Geomorph {
 public:
  static constexpr double kSeconds = 0.3;  ///< s of simulated time the wrinkles fade over

  /// At the switch from `fine` in `fine_state` to `coarse` in `coarse_state` (the same time).
  Geomorph(const sim::ClothModel<float>& fine, const sim::ClothState<float>& fine_state,
           const sim::ClothModel<float>& coarse, const sim::ClothState<float>& coarse_state);

  /// Whether frames of `coarse` at `time` still blend: the grid is the one it switched to and
  /// the fade has not run out.
  bool Blends(const sim::ClothModel<float>& coarse, double time) const;

  /// The fine grid's node positions to draw for `coarse_state` of `coarse` (Blends is true).
  void Draw(const sim::ClothModel<float>& coarse, const sim::ClothState<float>& coarse_state, std::vector<float>* x,
            std::vector<float>* y, std::vector<float>* z) const;

  int cols() const { return fine_.cols; }
  int rows() const { return fine_.rows; }

 private:
  sim::ClothModel<float> fine_;
  int coarse_cols_, coarse_rows_;
  double start_;                         ///< s, simulated: t0
  sim::NodeVectors<float> detail_;       ///< D on the fine grid, m
};

}  // namespace flagsim
