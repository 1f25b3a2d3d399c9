// Work against precision. The breeze preset (32 x 24 nodes, gusts on) for 0.2 s from rest;
// each integrator over seven steps halving from its stability limit or 1/60 s, and xpbd and
// projective at 2, 10 and 50 iterations. Error: against converged RK4, as RMS node distance
// (m) and on the default camera's 1280 x 720 image (px). Cost: CPU seconds per simulated
// second on one thread, in float as the server runs (median of three). bullet_bench
// --work-precision adds Bullet's soft body to the same table (work_precision_scene.hpp). The points are
// those scripts/sweep runs one by one elsewhere (sweep_points.hpp), here in turn.
#include "bench/lab/experiments.hpp"
#include "bench/lab/sweep_points.hpp"
#include "bench/lab/table.hpp"
#include "bench/lab/work_precision_scene.hpp"

namespace flagsim::lab {

void WorkPrecision(const std::string& csv) {
  std::optional<WorkPrecisionScene> scene = LoadWorkPrecisionScene();
  Table table(WorkPrecisionColumns(), csv);
  for (const Point& point : WorkPrecisionPoints(*scene, false)) table.Add(WorkPrecisionPointRow(point, &scene));
}

}  // namespace flagsim::lab
