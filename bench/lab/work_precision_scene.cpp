#include "bench/lab/work_precision_scene.hpp"

#include <cmath>

#include "bench/lab/lab_setup.hpp"
#include "bench/lab/table.hpp"
#include "lab/screen_error.hpp"
#include "server/scene/scene_file.hpp"

namespace flagsim::lab {
namespace {

constexpr char kPreset[] = "breeze";
constexpr double kHorizon = 0.2;           ///< s from rest: short enough that flutter stays orderly
constexpr double kReferenceTarget = 1e-8;  ///< m: the reference converges to a thousandth of this

}  // namespace

WorkPrecisionScene LoadWorkPrecisionScene(int reference_substeps) {
  WorkPrecisionScene scene;
  scene.trial = PresetTrial(kPreset, kHorizon);
  scene.camera = LoadScene(kPreset).camera;
  References references(scene.trial);
  scene.reference_substeps =
      reference_substeps > 0 ? reference_substeps : references.Converge(kReferenceTarget).substeps;
  scene.reference = references.At(scene.reference_substeps);
  return scene;
}

std::vector<std::string> WorkPrecisionColumns() {
  return {"integrator", "iterations", "h_s", "error_m", "error_px", "largest_px", "cost_s_per_s"};
}

std::vector<std::string> WorkPrecisionRow(const WorkPrecisionScene& scene, const std::string& method,
                                          const std::string& iterations, double h,
                                          const sim::ClothState<double>& state, double cost) {
  const bool sound = StateIsSound(state);
  const double error = sound ? RmsDistance(state, scene.reference) : INFINITY;
  const ScreenError pixels =
      sound ? ScreenDistance(scene.camera, state, scene.reference) : ScreenError{INFINITY, INFINITY};
  return {method,
          iterations,
          Table::Number(h),
          Table::Number(error),
          Table::Number(pixels.rms),
          Table::Number(pixels.largest),
          Table::Number(cost)};
}

}  // namespace flagsim::lab
