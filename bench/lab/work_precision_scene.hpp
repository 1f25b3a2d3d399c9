// What every point of the work-precision chart is measured on, whichever engine makes it: the
// flag (the breeze preset, 32 x 24 nodes, gusts on, 0.2 s from rest), the camera its error is
// seen through, the converged reference, and the CSV row that scores one run against it. The
// lab's own experiment and bullet_bench --work-precision both write their rows through these.
#pragma once

#include <string>
#include <vector>

#include "lab/trajectory.hpp"
#include "server/render/camera.hpp"
#include "server/sim/cloth_state.hpp"

namespace flagsim::lab {

struct WorkPrecisionScene {
  Trial trial;                        ///< the breeze preset over kHorizon s, one thread
  render::Camera camera;              ///< the preset's, 1280 x 720
  int reference_substeps = 0;         ///< RK4 in double over the horizon
  sim::ClothState<double> reference;  ///< the state at the horizon
};

/// The scene with its reference converged to 1e-11 m RMS (printed as a "# reference" line); or,
/// given `reference_substeps` (what a converged scene found), that reference run once.
WorkPrecisionScene LoadWorkPrecisionScene(int reference_substeps = 0);

/// The CSV's columns: integrator,iterations,h_s,error_m,error_px,largest_px,cost_s_per_s.
std::vector<std::string> WorkPrecisionColumns();

/// One row: `method` with `iterations` ("-" if it takes none) at step h (s) reached `state` at the
/// horizon, costing `cost` CPU s per simulated s. Error: RMS node distance to the reference (m),
/// and on the camera's image (px, RMS and largest), node i against node i; inf if state is unsound.
std::vector<std::string> WorkPrecisionRow(const WorkPrecisionScene& scene, const std::string& method,
                                          const std::string& iterations, double h,
                                          const sim::ClothState<double>& state, double cost);

}  // namespace flagsim::lab
