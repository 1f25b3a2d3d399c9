// Bullet's point on the work-precision chart. Rows, in the columns of `lab work-precision`:
//   bullet            BulletFlag (single precision, as Bullet is built) at h = 2 ms (and, with
//                     steps > 1, at 1 ms, 0.5 ms, ...) over the lab's 0.2 s; error against the lab's
//                     reference, node i against node i; cost: thread CPU seconds to build the flag and step
//                     it over the horizon, median of three, per simulated second (lab::CostPerSimulatedSecond
//                     does the same for flagsim: build the model, RunFixed<float>).
//   flagsim's         each integrator at the first step of the lab's sweep (0.9 of its limit),
//                     or at Bullet's 2 ms if it is unconditionally stable (10 iterations), as
//                     the lab measures it: the same figures as the chart's, timed in this run.
// Then "# model" lines (Bullet at 2 ms): converged flagsim (RK4, the reference's step) with, cumulatively,
// the gusts off (Bullet's wind is one velocity per body), no spring damping (Bullet's links have none) and
// the relative wind w - v (Bullet's aerodynamics): its distance from the reference (what the model change
// alone moves the flag) and Bullet's distance from it (what is left: Bullet's discretisation, its soft links,
// and the |w - v|^2 / |w|^2 and rest-area scaling of its wind, which flagsim cannot copy).
#include "bench/bullet_work_precision.hpp"

#include <cstdio>
#include <string>

#include "bench/bullet_flag.hpp"
#include "bench/lab/lab_setup.hpp"
#include "bench/lab/table.hpp"
#include "bench/lab/work_precision_scene.hpp"
#include "lab/screen_error.hpp"

namespace flagsim {
namespace {

constexpr double kBulletStep = 0.002;  ///< s, Bullet's step, as bullet_bench times it
constexpr int kCostRepeats = 3;        ///< runs timed, their median taken (the lab's)

/// Bullet's flag after trial.horizon s from rest in steps of h.
sim::ClothState<double> RunBullet(const lab::Trial& trial, double h, int iterations) {
  BulletFlag flag(trial.params, trial.wind, h, iterations);
  for (int i = lab::SubstepsFor(trial, h); i > 0; --i) flag.Step();
  return flag.State();
}

/// Bullet's row at a step close to `step` that fills the horizon; returns the state it reached.
sim::ClothState<double> AddBulletRow(const lab::WorkPrecisionScene& scene, double step, int iterations,
                                     lab::Table* table) {
  const double h = scene.trial.horizon / lab::SubstepsFor(scene.trial, step);
  const double cost = lab::MedianCpuSeconds(kCostRepeats, [&] { RunBullet(scene.trial, h, iterations); }) /
                      scene.trial.horizon;
  sim::ClothState<double> state = RunBullet(scene.trial, h, iterations);
  table->Add(lab::WorkPrecisionRow(scene, "bullet", std::to_string(iterations), h, state, cost));
  return state;
}

/// flagsim's `kind` as the lab's chart runs it, at one step (see the file's header).
void AddFlagsimRow(const lab::WorkPrecisionScene& scene, sim::IntegratorKind kind, lab::Table* table) {
  lab::Trial trial = scene.trial;
  trial.params.integrator = kind;
  const double h = lab::UnconditionallyStable(trial) ? kBulletStep : lab::StepSweep(trial, 1)[0];
  const int substeps = lab::SubstepsFor(trial, h);
  table->Add(
      lab::WorkPrecisionRow(scene, sim::IntegratorName(kind),
                            lab::TakesIterations(kind) ? std::to_string(trial.params.solver_iterations) : "-",
                            trial.horizon / substeps, lab::RunFixed<double>(trial, substeps),
                            lab::CostPerSimulatedSecond(trial, substeps, kCostRepeats)));
}

/// "distance m (RMS px)" from a to b, as the chart measures it.
std::string Distance(const lab::WorkPrecisionScene& scene, const sim::ClothState<double>& a,
                     const sim::ClothState<double>& b) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.3g m (%.3g px)", lab::RmsDistance(a, b),
                lab::ScreenDistance(scene.camera, a, b).rms);
  return text;
}

/// Converged flagsim in `trial`: how far from the reference, and how far Bullet is from it.
void PrintModelDifference(const lab::WorkPrecisionScene& scene, lab::Trial trial,
                          const sim::ClothState<double>& bullet, const char* change) {
  trial.params.integrator = sim::IntegratorKind::kRk4;
  const sim::ClothState<double> state = lab::RunFixed<double>(trial, scene.reference_substeps);
  std::printf("# model: converged flagsim %-32s %s from the reference; Bullet %s from it\n", change,
              Distance(scene, state, scene.reference).c_str(), Distance(scene, bullet, state).c_str());
}

/// The parts of Bullet's model flagsim can copy, one after another.
void PrintModelDifferences(const lab::WorkPrecisionScene& scene, const sim::ClothState<double>& bullet) {
  lab::Trial trial = scene.trial;
  trial.wind.gust = 0;
  PrintModelDifference(scene, trial, bullet, "with the gusts off:");
  trial.params.forces.damping = 0;
  PrintModelDifference(scene, trial, bullet, "and no spring damping:");
  trial.params.relative_wind = true;
  PrintModelDifference(scene, trial, bullet, "and the relative wind w - v:");
}

}  // namespace

void BulletWorkPrecision(int iterations, int steps, const std::string& csv) {
  const lab::WorkPrecisionScene scene = lab::LoadWorkPrecisionScene();
  sim::ClothState<double> bullet;
  {
    lab::Table table(lab::WorkPrecisionColumns(), csv);
    bullet = AddBulletRow(scene, kBulletStep, iterations, &table);
    for (int i = 1; i < steps; ++i) AddBulletRow(scene, kBulletStep / (1 << i), iterations, &table);
    for (const sim::IntegratorKind kind : lab::AllIntegrators()) AddFlagsimRow(scene, kind, &table);
  }  // the CSV is written here
  PrintModelDifferences(scene, bullet);
}

}  // namespace flagsim
