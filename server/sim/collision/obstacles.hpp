// The pole and the ground, as the cloth meets them. The pole is a cylinder of radius R about
// the y axis from the ground to its top; the ground is the plane y = 0. A node keeps half the
// cloth's thickness h from both:
//   pole    sqrt(x^2 + z^2) >= R + h/2  wherever y < top      ground  y >= h/2
// A node found inside is moved to the nearest surface point, its velocity into the surface is
// removed (an inelastic contact), and Coulomb friction takes up to mu times that change from its
// sliding speed: |v_t| <- max(0, |v_t| - mu |dv_n|). Nodes pinned to the pole are left alone.
#pragma once

#include "server/sim/cloth_model.hpp"
#include "server/sim/cloth_state.hpp"
#include "server/sim/sim_params.hpp"

namespace flagsim::sim {

struct Obstacles {
  double pole_radius = 0;  ///< m, R
  double pole_top = 0;     ///< m
  double margin = 0;       ///< m, h/2: nodes keep this far from the pole's side and the ground
  double friction = 0;     ///< Coulomb coefficient, pole and ground

  static Obstacles Of(const SimParams& params);
  /// True when the point is inside the pole or below the ground (the surfaces themselves,
  /// without the margin).
  bool Inside(double x, double y, double z) const;
};

/// Moves every free node of `state` out of the pole and the ground as above, on `threads` threads.
template <typename Real>
void PushOutOfObstacles(const ClothModel<Real>& model, const Obstacles& obstacles, int threads,
                        ClothState<Real>* state);

}  // namespace flagsim::sim
