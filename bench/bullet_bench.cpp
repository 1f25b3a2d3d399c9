// flagsim's flag beside Bullet's soft body (btSoftBody, Bullet 3.24) on the same flag: the time
// per 2 ms step on one thread and the largest stable step of each method, at three grid sizes.
//
//   build/bench/bullet_bench [--csv FILE] [--repetitions N] [--horizon S] [--iterations N]
//
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
// Bullet's flag (BulletFlag below), built from nodes, links and faces with the public API:
//   links      flagsim's six spring families, one material each: structural (0,1) (1,0), shear
//              (1,1) (1,-1), bend (0,2) (2,0). Appended by hand rather than by CreatePatch (one
//              diagonal per cell) and generateBendingConstraints(2) (on a grid it also links the
//              diagonals, or knight's moves once diagonals exist, and builds an n^2 adjacency
//              matrix: 600 MB at 128 x 96).
//   stiffness  kLST from each family's spring constant k, see LinkStiffness: not an exact match.
//              Bullet's links have no damping: flagsim's spring damping is left out.
//   air        kDP = 1 - exp(-friction h), flagsim's air friction over one step.
//   wind       aeromodel F_TwoSided: per face rho kLF 2A0 (n.u) |u|^2 n, A0 its rest area,
//              u = w - v, a third to each node (a share that would change a node's velocity by
//              more than its speed in one step is cut to one that stops it along the share).
//              kLF = C / (2 rho |w|^2) makes it flagsim's C A (n.w) n when |u| = |w| and A = A0;
//              kDG = 0, as flagsim's law has no drag along the wind.
//   solver     m_cfg.piterations = --iterations, btSoftRigidDynamicsWorld::stepSimulation(h, 0):
//              exactly one internal step of h.
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
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lab/trajectory.hpp"
#include "scene_file.hpp"
#include "sim/cloth_model.hpp"
#include "sim/integrator.hpp"
#include "sim/simulation.hpp"

namespace flagsim {
namespace {

constexpr std::pair<int, int> kFlagGrids[] = {{32, 24}, {64, 48}, {128, 96}};  ///< nodes
constexpr sim::IntegratorKind kMethods[] = {sim::IntegratorKind::kSymplecticEuler,
                                            sim::IntegratorKind::kVelocityVerlet, sim::IntegratorKind::kRk4,
                                            sim::IntegratorKind::kXpbd, sim::IntegratorKind::kImplicitEuler};
constexpr double kStep = 0.002;          ///< s, the step timed
constexpr double kWarmup = 0.1;          ///< s of simulated time before timing
constexpr double kRepetitionCpu = 0.05;  ///< s of CPU time per timed repetition, about
constexpr double kAirDensity = 1.2;      ///< kg/m^3, Bullet's rho
constexpr double kRunawaySpeed = lab::kRunawaySpeed;  ///< m/s: a node faster than this is a blow-up
constexpr double kSmallestStep = 1e-6;   ///< s, the stability search's range
constexpr double kLargestStep = 0.05;    ///< s
constexpr double kStepPrecision = 1.05;  ///< the search stops when hi / lo is at most this

struct Options {
  int repetitions = 7;
  double horizon = 2.0;  ///< s
  int iterations = 10;   ///< Bullet's piterations
  std::string csv_path;  ///< "" writes no CSV
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
    } else {
      return false;
    }
  }
  return options->repetitions >= 1 && options->horizon > 0 && options->iterations >= 1;
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

/// s of CPU time used by the calling thread.
double ThreadSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

/// step() timed => median ms of CPU time per call over `repetitions` repetitions, each of as many
/// calls as one call's time says fit in kRepetitionCpu.
double MedianStepMs(int repetitions, const std::function<void()>& step) {
  const double start = ThreadSeconds();
  step();
  const double once = ThreadSeconds() - start;
  const int calls = std::max(1, int(kRepetitionCpu / std::max(once, 1e-9)));
  std::vector<double> ms;
  for (int r = 0; r < repetitions; ++r) {
    const double begin = ThreadSeconds();
    for (int i = 0; i < calls; ++i) step();
    ms.push_back(1e3 * (ThreadSeconds() - begin) / calls);
  }
  std::sort(ms.begin(), ms.end());
  const size_t middle = ms.size() / 2;
  return ms.size() % 2 == 1 ? ms[middle] : 0.5 * (ms[middle - 1] + ms[middle]);
}

/// Bullet's kLST for a spring of constant k (N/m) whose nodes' inverse masses sum to w (1/kg), at
/// step h (s) with n position iterations. An XPBD projection of the spring as a constraint of
/// compliance 1/k closes the fraction f = k h^2 w / (1 + k h^2 w) of its error in one step (what
/// backward Euler does to the spring alone); Bullet closes kLST of it per iteration, so n
/// iterations on a lone link close 1 - (1 - kLST)^n. Hence kLST = 1 - (1 - f)^(1/n). Coupled
/// links converge more slowly under Gauss-Seidel, so the sheet comes out softer than flagsim's.
double LinkStiffness(double k, double w, double h, int n) {
  const double stiffness = k * h * h * w;
  const double fraction = stiffness / (1 + stiffness);
  return 1 - std::pow(1 - fraction, 1.0 / n);
}

/// The flag of `scene` as a Bullet soft body alone in a soft-rigid world, stepped by h.
class BulletFlag {
 public:
  BulletFlag(const Scene& scene, double h, int iterations) : h_(h) {
    const sim::ClothModel<double> model = sim::BuildClothModel<double>(scene.sim);
    AddBody(model);
    AddLinks(model, iterations);
    AddFaces(model);
    Configure(scene, iterations);
    world_.addSoftBody(body_.get());
  }
  ~BulletFlag() { world_.removeSoftBody(body_.get()); }
  BulletFlag(const BulletFlag&) = delete;
  BulletFlag& operator=(const BulletFlag&) = delete;

  /// One internal step of exactly h (maxSubSteps = 0: no fixed-step accumulator).
  void Step() { world_.stepSimulation(btScalar(h_), 0); }

  /// Every position and velocity finite and no velocity component above `runaway` m/s.
  bool IsSound(double runaway) const {
    for (int i = 0; i < body_->m_nodes.size(); ++i) {
      const btSoftBody::Node& node = body_->m_nodes[i];
      for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(node.m_x[k]) || !(std::abs(node.m_v[k]) <= runaway)) return false;
      }
    }
    return true;
  }

  /// kLST per spring family, in ClothModel::families order.
  const std::vector<double>& link_stiffness() const { return link_stiffness_; }

 private:
  // Node (r, c) at flagsim's rest position, with flagsim's mass; 0 (pinned) on the hoist column.
  void AddBody(const sim::ClothModel<double>& model) {
    const int n = model.num_nodes();
    std::vector<btVector3> positions(n);
    std::vector<btScalar> masses(n);
    for (int i = 0; i < n; ++i) {
      positions[i] =
          btVector3(btScalar(model.rest_x[i]), btScalar(model.rest_y[i]), btScalar(model.rest_z[i]));
      masses[i] = model.pinned(i) ? btScalar(0) : btScalar(model.mass[i]);
    }
    body_ = std::make_unique<btSoftBody>(&world_.getWorldInfo(), n, positions.data(), masses.data());
  }

  // Each family a material, its kLST mapped from the spring constant with w = 2 / m of an
  // interior node; one link per flagsim spring (r, c) -> (r + dr, c + dc).
  void AddLinks(const sim::ClothModel<double>& model, int iterations) {
    const double w = 2 * model.inverse_mass[model.index(1, 1)];
    for (const sim::SpringFamily<double>& family : model.families) {
      btSoftBody::Material* material = body_->appendMaterial();
      material->m_kLST = btScalar(LinkStiffness(family.stiffness, w, h_, iterations));
      link_stiffness_.push_back(material->m_kLST);
      for (int r = 0; r + family.dr < model.rows; ++r) {
        for (int c = family.first_col(); c < family.end_col(model.cols); ++c) {
          body_->appendLink(model.index(r, c), model.index(r + family.dr, c + family.dc), material);
        }
      }
    }
  }

  // flagsim's two triangles per cell, in its winding: upper (r, c) (r+1, c) (r, c+1), lower
  // (r+1, c) (r+1, c+1) (r, c+1).
  void AddFaces(const sim::ClothModel<double>& model) {
    for (int r = 0; r + 1 < model.rows; ++r) {
      for (int c = 0; c + 1 < model.cols; ++c) {
        body_->appendFace(model.index(r, c), model.index(r + 1, c), model.index(r, c + 1));
        body_->appendFace(model.index(r + 1, c), model.index(r + 1, c + 1), model.index(r, c + 1));
      }
    }
  }

  // Gravity, air friction, wind and solver as the file's header describes.
  void Configure(const Scene& scene, int iterations) {
    const btVector3 gravity(0, btScalar(-scene.sim.gravity), 0);
    world_.setGravity(gravity);
    world_.getWorldInfo().m_gravity = gravity;
    world_.getWorldInfo().air_density = btScalar(kAirDensity);
    const sim::Vec3& wind = scene.wind.velocity;
    const double speed_squared = wind[0] * wind[0] + wind[1] * wind[1] + wind[2] * wind[2];
    btSoftBody::Config& config = body_->m_cfg;
    config.piterations = iterations;
    config.kDP = btScalar(1 - std::exp(-scene.sim.friction * h_));
    config.aeromodel = btSoftBody::eAeroModel::F_TwoSided;
    config.kLF = btScalar(scene.sim.wind_coefficient / (2 * kAirDensity * speed_squared));
    config.kDG = 0;
    body_->setWindVelocity(btVector3(btScalar(wind[0]), btScalar(wind[1]), btScalar(wind[2])));
  }

  double h_;  ///< s per step
  btSoftBodyRigidBodyCollisionConfiguration collision_configuration_;
  btCollisionDispatcher dispatcher_{&collision_configuration_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btSoftRigidDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &collision_configuration_};
  std::unique_ptr<btSoftBody> body_;
  std::vector<double> link_stiffness_;
};

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
  BulletFlag flag(scene, h, iterations);
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
  BulletFlag flag(scene, kStep, options.iterations);
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
  const BulletFlag flag(scene, kStep, options.iterations);
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
    std::fprintf(stderr, "usage: %s [--csv FILE] [--repetitions N] [--horizon S] [--iterations N]\n",
                 argv[0]);
    return 2;
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
