// flagsim's flag beside Bullet's soft body (btSoftBody, Bullet 3.24) on the same flag: the time
// per 2 ms step on one thread and the largest stable step of each method, at three grid sizes.
//
//   build/bench/bullet_bench [--csv FILE] [--repetitions N] [--horizon S] [--iterations N]
//   build/bench/bullet_bench --work-precision [--csv FILE] [--iterations N] [--steps N]
//
// --work-precision  instead, Bullet's point on the lab's work-precision chart: its error against
//                   the lab's reference and its cost, as `lab work-precision` rows (and flagsim's
//                   integrators timed in the same run; bullet_work_precision.cpp)
// --steps N         with --work-precision: Bullet at 2 ms and N - 1 halvings of it (default 1)
// --csv FILE        also write the table as CSV: grid,nodes,engine,method,substeps,ms_per_step,
//                   bullet_over_this,stable_step_ms,stable_bound (=, >= or <)
// --repetitions N   timed repetitions per method, their median reported (default 7)
// --horizon S       simulated seconds a step size must survive to count as stable (default 2)
// --iterations N    Bullet's position solver iterations, m_cfg.piterations (default 10)
//
// The flag, in both engines: the breeze scene (LoadScene("breeze")) at cols x rows nodes, 1.5 m x
// 1.0 m, 0.25 kg lumped by area (flagsim's node masses, handed to Bullet as they are), the hoist
// column pinned (mass 0 in Bullet), gravity 9.81 m/s^2 down, a steady wind (6, 0, 1.5) m/s: the
// breeze without its gusts, since Bullet's wind is one velocity per body.
//
// Bullet's flag: BulletFlag (bullet_flag.hpp), which says how each quantity is matched.
//
// What is measured:
//   time    CPU time of this thread (CLOCK_THREAD_CPUTIME_ID) per 2 ms step, after 0.1 s of
//           simulated time from rest; median over the repetitions, each of as many steps as take
//           about 50 ms. flagsim: Simulation<float>::Step with threads = 1 and its own substeps
//           (reported), so an explicit method's time includes all of its substeps. Bullet:
//           stepSimulation(0.002, 0).
//   stable  the largest step h from which a flag at rest, run for --horizon seconds in steps of
//           h, ends with every position and velocity finite and no node faster than 100 m/s
//           (per component). flagsim: lab::RunFixed (double precision, one substep per step, no
//           guard) and lab::StateIsSound; Bullet: stepSimulation(h, 0) in single precision, its
//           kLST and kDP mapped for h. Found by doubling or halving from a first guess, then
//           bisecting geometrically to 5 %; searched within [1 us, 50 ms].
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "bench/bullet_flag.hpp"
#include "bench/bullet_work_precision.hpp"
#include "lab/cpu_time.hpp"
#include "lab/trajectory.hpp"
#include "server/scene/scene_file.hpp"
#include "server/sim/cloth_model.hpp"
#include "server/sim/integrator.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim {
namespace {

constexpr std::pair<int, int> kFlagGrids[] = {{32, 24}, {64, 48}, {128, 96}};  ///< nodes
constexpr sim::IntegratorKind kMethods[] = {sim::IntegratorKind::kSymplecticEuler,
                                            sim::IntegratorKind::kVelocityVerlet, sim::IntegratorKind::kRk4,
                                            sim::IntegratorKind::kXpbd, sim::IntegratorKind::kImplicitEuler};
constexpr double kStep = 0.002;                       ///< s, the step timed
constexpr double kWarmup = 0.1;                       ///< s of simulated time before timing
constexpr double kRepetitionCpu = 0.05;               ///< s of CPU time per timed repetition, about
constexpr double kRunawaySpeed = lab::kRunawaySpeed;  ///< m/s: a node faster than this is a blow-up
constexpr double kSmallestStep = 1e-6;                ///< s, the stability search's range
constexpr double kLargestStep = 0.05;                 ///< s
constexpr double kStepPrecision = 1.05;               ///< the search stops when hi / lo is at most this

struct Options {
  int repetitions = 7;
  double horizon = 2.0;         ///< s
  int iterations = 10;          ///< Bullet's piterations
  std::string csv_path;         ///< "" writes no CSV
  bool work_precision = false;  ///< Bullet's point on the work-precision chart instead
  int steps = 1;                ///< --work-precision: 2 ms and steps - 1 halvings
};

/// The largest stable step, or a bound on it when the search range ends first.
struct StableStep {
  double h = 0;             ///< s
  std::string bound = "=";  ///< "=" found, ">=" stable at kLargestStep, "<" unstable at kSmallestStep
};

/// One line of the table.
struct Row {
  int cols = 0, rows = 0;  ///< nodes
  std::string engine, method;
  int substeps = 1;         ///< per 2 ms step
  double ms = 0;            ///< median CPU time per 2 ms step
  double bullet_ratio = 0;  ///< Bullet's ms / this row's ms
  StableStep stable;
};

bool ParseOptions(int argc, char** argv, Options* options) {
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--work-precision") {
      options->work_precision = true;
      continue;
    }
    if (i + 1 >= argc) return false;
    const std::string value = argv[++i];
    if (flag == "--csv") {
      options->csv_path = value;
    } else if (flag == "--repetitions") {
      options->repetitions = std::atoi(value.c_str());
    } else if (flag == "--horizon") {
      options->horizon = std::atof(value.c_str());
    } else if (flag == "--iterations") {
      options->iterations = std::atoi(value.c_str());
    } else if (flag == "--steps") {
      options->steps = std::atoi(value.c_str());
    } else {
      return false;
    }
  }
  return options->repetitions >= 1 && options->horizon > 0 && options->iterations >= 1 &&
         options->steps >= 1 && options->steps <= 12;
}

/// The breeze scene at cols x rows nodes on one thread, its gusts off.
Scene FlagScene(int cols, int rows) {
  Scene scene = LoadScene("breeze");
  scene.sim.cols = cols;
  scene.sim.rows = rows;
  scene.sim.threads = 1;
  scene.wind.gust = 0;
  return scene;
}

/// step() timed => median ms of CPU time per call over `repetitions` repetitions, each of as many
/// calls as one call's time says fit in kRepetitionCpu.
double MedianStepMs(int repetitions, const std::function<void()>& step) {
  const double start = lab::ThreadCpuSeconds();
  step();
  const double once = lab::ThreadCpuSeconds() - start;
  const int calls = std::max(1, int(kRepetitionCpu / std::max(once, 1e-9)));
  std::vector<double> ms;
  for (int r = 0; r < repetitions; ++r) {
    const double begin = lab::ThreadCpuSeconds();
    for (int i = 0; i < calls; ++i) step();
    ms.push_back(1e3 * (lab::ThreadCpuSeconds() - begin) / calls);
  }
  std::sort(ms.begin(), ms.end());
  const size_t middle = ms.size() / 2;
  return ms.size() % 2 == 1 ? ms[middle] : 0.5 * (ms[middle - 1] + ms[middle]);
}

/// Steps that make up `seconds` of simulated time at step h, at least one.
int StepsFor(double seconds, double h) { return std::max(1, int(std::lround(seconds / h))); }

/// `stable` a predicate on h, `guess` where to start => the largest stable h within
/// [kSmallestStep, kLargestStep]: h doubled (or halved) from the guess until stability changes,
/// then the bracket [lo, hi] bisected geometrically until hi / lo <= kStepPrecision.
StableStep LargestStableStep(const std::function<bool(double)>& stable, double guess) {
  double lo = std::clamp(guess, kSmallestStep, kLargestStep), hi = lo;
  if (stable(lo)) {
    while (lo < kLargestStep && stable(hi = std::min(2 * lo, kLargestStep))) lo = hi;
    if (lo == kLargestStep) return {kLargestStep, ">="};
  } else {
    while (hi > kSmallestStep && !stable(lo = std::max(hi / 2, kSmallestStep))) hi = lo;
    if (hi == kSmallestStep) return {kSmallestStep, "<"};
  }
  while (hi / lo > kStepPrecision) {
    const double middle = std::sqrt(lo * hi);
    (stable(middle) ? lo : hi) = middle;
  }
  return {lo, "="};
}

/// Whether flagsim's `method` survives `horizon` seconds in steps of h: one substep per step.
bool FlagsimStable(const Scene& scene, sim::IntegratorKind method, double horizon, double h) {
  lab::Trial trial{scene.sim, scene.wind, scene.seed, horizon};
  trial.params.integrator = method;
  trial.params.substeps = 1;
  trial.params.dt = h;
  return lab::StateIsSound(lab::RunFixed<double>(trial, StepsFor(horizon, h)));
}

/// Whether Bullet's flag survives `horizon` seconds in steps of h.
bool BulletStable(const Scene& scene, int iterations, double horizon, double h) {
  BulletFlag flag(scene.sim, scene.wind, h, iterations);
  for (int i = StepsFor(horizon, h); i > 0; --i) flag.Step();
  return flag.IsSound(kRunawaySpeed);
}

/// flagsim's explicit limit from the grid's frequency bound (no safety factor), else 2 ms.
double FirstGuess(const Scene& scene, sim::IntegratorKind method) {
  sim::SimParams params = scene.sim;
  params.integrator = method;
  const sim::ClothModel<double> model = sim::BuildClothModel<double>(params);
  const double limit = sim::MakeIntegrator<double>(method)->StableStep(
      sim::EstimateFrequencyBound(model, sim::AirFriction(params)));
  return std::isfinite(limit) ? limit : kStep;
}

Row MeasureFlagsim(const Scene& scene, sim::IntegratorKind method, const Options& options) {
  Scene timed = scene;
  timed.sim.integrator = method;
  sim::Simulation<float> simulation(timed.sim, timed.wind, timed.seed);
  for (int i = StepsFor(kWarmup, kStep); i > 0; --i) simulation.Step();
  Row row;
  row.cols = scene.sim.cols;
  row.rows = scene.sim.rows;
  row.engine = "flagsim";
  row.method = sim::IntegratorName(method);
  row.ms = MedianStepMs(options.repetitions, [&] { simulation.Step(); });
  row.substeps = simulation.substeps();
  row.stable = LargestStableStep([&](double h) { return FlagsimStable(scene, method, options.horizon, h); },
                                 FirstGuess(scene, method));
  return row;
}

Row MeasureBullet(const Scene& scene, const Options& options) {
  BulletFlag flag(scene.sim, scene.wind, kStep, options.iterations);
  for (int i = StepsFor(kWarmup, kStep); i > 0; --i) flag.Step();
  Row row;
  row.cols = scene.sim.cols;
  row.rows = scene.sim.rows;
  row.engine = "bullet";
  row.method = "stepSimulation";
  row.ms = MedianStepMs(options.repetitions, [&] { flag.Step(); });
  row.stable = LargestStableStep(
      [&](double h) { return BulletStable(scene, options.iterations, options.horizon, h); }, kStep);
  return row;
}

std::string GridName(int cols, int rows) { return std::to_string(cols) + "x" + std::to_string(rows); }

/// The mapped kLST of each spring family at the timed step.
void PrintLinkStiffness(const Scene& scene, const Options& options) {
  const BulletFlag flag(scene.sim, scene.wind, kStep, options.iterations);
  const std::vector<double>& k = flag.link_stiffness();
  std::printf("%s Bullet kLST at h = 2 ms: structural %.3f %.3f, shear %.3f %.3f, bend %.4f %.4f\n",
              GridName(scene.sim.cols, scene.sim.rows).c_str(), k[0], k[1], k[2], k[3], k[4], k[5]);
}

void PrintHeader() {
  std::printf("%-8s %-8s %-17s %8s %11s %13s %14s\n", "grid", "engine", "method", "substeps", "ms/step",
              "bullet/this", "stable h (ms)");
}

void PrintRow(const Row& row) {
  std::printf("%-8s %-8s %-17s %8d %11.4f %12.2fx %3s %10.4f\n", GridName(row.cols, row.rows).c_str(),
              row.engine.c_str(), row.method.c_str(), row.substeps, row.ms, row.bullet_ratio,
              row.stable.bound.c_str(), 1e3 * row.stable.h);
  std::fflush(stdout);
}

/// table => CSV at `path`; false if it could not be written.
bool WriteCsv(const std::string& path, const std::vector<Row>& table) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (!file) return false;
  std::fprintf(
      file, "grid,nodes,engine,method,substeps,ms_per_step,bullet_over_this,stable_step_ms,stable_bound\n");
  for (const Row& row : table) {
    std::fprintf(file, "%s,%d,%s,%s,%d,%.5f,%.3f,%.5f,%s\n", GridName(row.cols, row.rows).c_str(),
                 row.cols * row.rows, row.engine.c_str(), row.method.c_str(), row.substeps, row.ms,
                 row.bullet_ratio, 1e3 * row.stable.h, row.stable.bound.c_str());
  }
  return std::fclose(file) == 0;
}

/// Bullet first, so that each flagsim row can be given Bullet's time over its own.
void MeasureGrid(int cols, int rows, const Options& options, std::vector<Row>* table) {
  const Scene scene = FlagScene(cols, rows);
  PrintLinkStiffness(scene, options);
  Row bullet = MeasureBullet(scene, options);
  bullet.bullet_ratio = 1;
  PrintRow(bullet);
  table->push_back(bullet);
  for (const sim::IntegratorKind method : kMethods) {
    Row row = MeasureFlagsim(scene, method, options);
    row.bullet_ratio = bullet.ms / row.ms;
    PrintRow(row);
    table->push_back(row);
  }
}

}  // namespace
}  // namespace flagsim

int main(int argc, char** argv) {
  flagsim::Options options;
  if (!flagsim::ParseOptions(argc, argv, &options)) {
    std::fprintf(stderr,
                 "usage: %s [--csv FILE] [--repetitions N] [--horizon S] [--iterations N]\n"
                 "       %s --work-precision [--csv FILE] [--iterations N] [--steps N]\n",
                 argv[0], argv[0]);
    return 2;
  }
  if (options.work_precision) {
    flagsim::BulletWorkPrecision(options.iterations, options.steps, options.csv_path);
    return 0;
  }
  std::printf("breeze flag, steady wind; 1 thread; time: thread CPU ms per 2 ms step, median of %d\n",
              options.repetitions);
  std::printf(
      "Bullet: piterations %d, F_TwoSided wind; stable: %.3g s from rest in steps of h ends finite,\n"
      "no node faster than %.0f m/s (flagsim: one substep per step, double; Bullet: float)\n",
      options.iterations, options.horizon, flagsim::kRunawaySpeed);
  flagsim::PrintHeader();
  std::vector<flagsim::Row> table;
  for (const auto& [cols, rows] : flagsim::kFlagGrids) flagsim::MeasureGrid(cols, rows, options, &table);
  if (!options.csv_path.empty() && !flagsim::WriteCsv(options.csv_path, table)) {
    std::fprintf(stderr, "bullet_bench: cannot write %s\n", options.csv_path.c_str());
    return 1;
  }
  return 0;
}
