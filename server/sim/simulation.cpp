#include "server/sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <stdexcept>

#include "server/sim/resample.hpp"

namespace flagsim::sim {
namespace {

bool GridChanged(const SimParams& a, const SimParams& b) {
  return a.cols != b.cols || a.rows != b.rows || a.width != b.width || a.height != b.height ||
         a.mass != b.mass || a.pole_height != b.pole_height || a.pole_radius != b.pole_radius ||
         a.imperfection != b.imperfection;
}

std::string Format(const char* format, double value) {
  char text[96];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

/// The largest |d|^2 / L^2 over the structural springs.
template <typename Real>
Real LargestStretchSquared(const ClothModel<Real>& model, const ClothState<Real>& state) {
  Real largest = 0;
  const Real *x = state.x.data(), *y = state.y.data(), *z = state.z.data();
  for (const SpringFamily<Real>& family : model.families) {
    if (family.kind != SpringKind::kStructural || family.rest_length <= 0) continue;
    const Real inverse_rest_squared = Real(1) / (family.rest_length * family.rest_length);
    const int offset = family.dr * model.cols + family.dc;
    for (int r = 0; r + family.dr < model.rows; ++r) {
      const int begin = model.index(r, family.first_col()), end = model.index(r, family.end_col(model.cols));
#pragma omp simd reduction(max : largest)
      for (int a = begin; a < end; ++a) {
        const Real dx = x[a + offset] - x[a], dy = y[a + offset] - y[a], dz = z[a + offset] - z[a];
        largest = std::max(largest, (dx * dx + dy * dy + dz * dz) * inverse_rest_squared);
      }
    }
  }
  return largest;
}

template <typename Real>
bool AllSized(size_t size, std::initializer_list<const std::vector<Real>*> vectors) {
  return std::all_of(vectors.begin(), vectors.end(), [size](const auto* v) { return v->size() == size; });
}

}  // namespace

std::string GuardEvent::Describe() const {
  if (step < 0) return "";
  return "step " + std::to_string(step) + ": " + problem + "; " + action;
}

int SubstepsFor(const SimParams& params) { return SubstepsForRange(params, params); }

int SubstepsForRange(const SimParams& least, const SimParams& most) {
  if (most.substeps > 0) return most.substeps;
  // w^2 and the damping rate at the most of everything; the ratio at the least damping per
  // stiffness (the model's damping lowered to the least); friction at the least.
  ClothModel<double> model = BuildClothModel<double>(most);
  FrequencyBound bound = EstimateFrequencyBound(model, AirFriction(most));
  SimParams least_damped = most;
  least_damped.forces.damping = least.forces.damping;
  SetMaterialConstants(least_damped, &model);
  bound.stiffness_damping_ratio = StiffnessDampingRatio(model);
  bound.friction = AirFriction(least);
  const double stable =
      Simulation<double>::kSafety * MakeIntegrator<double>(most.integrator)->StableStep(bound);
  const double needed = std::ceil(most.dt / stable);
  return static_cast<int>(std::clamp(needed, 1.0, double(kMaxComputedSubsteps)));
}

template <typename Real>
Simulation<Real>::Simulation(const SimParams& params, const WindSettings& wind, uint64_t seed)
    : params_(params), wind_(wind, seed) {
  BuildModel();
  ChooseIntegrator();
  state_ = RestState(model_);
  Checkpoint();
}

template <typename Real>
Simulation<Real>::Simulation(const SimulationSnapshot<Real>& snapshot)
    : params_(snapshot.params),
      state_(snapshot.state),
      wind_(snapshot.wind),
      guard_factor_(snapshot.guard_factor),
      recoveries_(snapshot.recoveries),
      good_steps_(snapshot.good_steps),
      sleeping_(snapshot.sleeping) {
  BuildModel();
  if (state_.num_nodes() != model_.num_nodes())
    throw std::invalid_argument("snapshot: the state has " + std::to_string(state_.num_nodes()) +
                                " nodes, its parameters make " + std::to_string(model_.num_nodes()));
  integrator_ = MakeIntegrator<Real>(params_.integrator);
  SetSubsteps(snapshot.substeps);
  Carry(snapshot.carried);
}

// Each carried vector is empty or holds a value per node: anything else is another grid's.
template <typename Real>
void Simulation<Real>::Carry(const CarriedState<Real>& carried) {
  const size_t n = model_.num_nodes();
  const NodeVectors<Real>& memory = carried.integrator;
  const ClothState<Real>& rollback = carried.rollback;
  const NodeVectors<Real>& calm = carried.calm_start;
  const auto memory_sized = [&](size_t size) { return AllSized(size, {&memory.x, &memory.y, &memory.z}); };
  const auto rollback_sized = [&](size_t size) {
    return AllSized(size, {&rollback.x, &rollback.y, &rollback.z, &rollback.vx, &rollback.vy, &rollback.vz});
  };
  const bool fits = (memory_sized(0) || memory_sized(n)) && (rollback_sized(0) || rollback_sized(n)) &&
                    (carried.calm_steps <= 0 || AllSized(n, {&calm.x, &calm.y, &calm.z}));
  if (!fits)
    throw std::invalid_argument("snapshot: what it carries does not fit its " + std::to_string(n) + " nodes");
  integrator_->Recall(memory);
  checkpoint_ = rollback_sized(0) ? state_ : rollback;
  calm_steps_ = std::max(0, carried.calm_steps);
  if (calm_steps_ > 0) calm_start_ = calm;
}

template <typename Real>
SimulationSnapshot<Real> Simulation<Real>::Snapshot() const {
  CarriedState<Real> carried;
  carried.integrator = integrator_->Memory();
  if (checkpoint_.step != state_.step) carried.rollback = checkpoint_;
  carried.calm_steps = calm_steps_;
  if (calm_steps_ > 0) carried.calm_start = calm_start_;
  return {params_,     wind_.State(), state_,    substeps_, guard_factor_,
          good_steps_, recoveries_,   sleeping_, carried};
}

template <typename Real>
void Simulation<Real>::BuildModel() {
  model_ = BuildClothModel<Real>(params_);
  self_collision_ = std::make_unique<SelfCollision<Real>>(model_);
}

template <typename Real>
void Simulation<Real>::ChooseIntegrator() {
  integrator_ = MakeIntegrator<Real>(params_.integrator);
  substeps_ = SubstepsFor(params_);
}

template <typename Real>
void Simulation<Real>::SetParams(const SimParams& params) {
  const bool regrid = GridChanged(params, params_);
  params_ = params;
  Wake();
  if (regrid) {
    BuildModel();
  } else {
    SetMaterialConstants(params_, &model_);
  }
  ChooseIntegrator();
  if (regrid) RestartFlag();
  Checkpoint();
}

template <typename Real>
void Simulation<Real>::Regrid(int cols, int rows) {
  if (cols == params_.cols && rows == params_.rows) return;
  const ClothModel<Real> old_model = std::move(model_);
  params_.cols = cols;
  params_.rows = rows;
  BuildModel();
  ChooseIntegrator();
  RestartFlag(Resample(old_model, state_, model_));
}

template <typename Real>
void Simulation<Real>::SetWind(const WindSettings& wind) {
  wind_.Set(wind, state_.time);
  Wake();
  integrator_->Reset();
  Checkpoint();  // a rollback must not replay earlier steps under the new wind
}

template <typename Real>
void Simulation<Real>::SetControls(const ForceCoefficients& forces, const WindSettings& wind) {
  const bool changed = forces != params_.forces;
  const WindSettings& now = wind_.target();
  const bool blows =
      wind.velocity != now.velocity || wind.gust != now.gust || wind.ramp_time != now.ramp_time;
  params_.forces = forces;
  if (changed) SetMaterialConstants(params_, &model_);
  if (blows) wind_.Set(wind, state_.time);
  if (changed || blows) Wake();
}

template <typename Real>
void Simulation<Real>::SetSubsteps(int substeps) {
  substeps_ = std::clamp(substeps, 1, kMaxComputedSubsteps);
}

template <typename Real>
void Simulation<Real>::RestartFlag() {
  RestartFlag(RestState(model_));
}

template <typename Real>
void Simulation<Real>::RestartFlag(const ClothState<Real>& pose) {
  const double time = state_.time;
  const int64_t step = state_.step;
  state_ = pose;
  state_.time = time;
  state_.step = step;
  Wake();
  integrator_->Reset();
  Checkpoint();
}

template <typename Real>
void Simulation<Real>::Step() {
  if (sleeping_) {
    state_.time += params_.dt;
    ++state_.step;
    return;
  }
  if (state_.step % kCheckpointInterval == 0) Checkpoint();
  double fastest = 0;
  const std::string problem = Advance(&fastest);
  if (!problem.empty()) {
    Recover(problem);
    calm_steps_ = 0;
    return;
  }
  if (guard_factor_ > 1 && ++good_steps_ >= 64 * kCheckpointInterval) {
    guard_factor_ /= 2;  // the trouble has passed: relax towards the stability limit
    good_steps_ = 0;
  }
  WatchForSleep(fastest);
}

// Calm air: every kStepsToSleep steps, compare the pose with the one at the start of the run.
template <typename Real>
void Simulation<Real>::WatchForSleep(double fastest) {
  const Vec3 mean = wind_.Mean(state_.time), target = wind_.target().velocity;
  if (!(mean == Vec3{0, 0, 0} && target == Vec3{0, 0, 0})) {
    calm_steps_ = 0;
    return;
  }
  if (calm_steps_ == 0) calm_start_ = {state_.x, state_.y, state_.z};
  if (++calm_steps_ < kStepsToSleep) return;
  calm_steps_ = 0;
  Real farthest = 0;
  for (int i = 0; i < state_.num_nodes(); ++i) {
    farthest = std::max({farthest, std::abs(state_.x[i] - calm_start_.x[i]),
                         std::abs(state_.y[i] - calm_start_.y[i]), std::abs(state_.z[i] - calm_start_.z[i])});
  }
  sleeping_ = farthest < Real(kSleepDistance) && fastest < kSleepSpeed;
}

template <typename Real>
void Simulation<Real>::Wake() {
  sleeping_ = false;
  calm_steps_ = 0;
}

// The integrator's substeps, the obstacles after each, and self-collision on a sound result
// after every group of substeps (CollisionPasses). Returns Problem() of the end state.
template <typename Real>
std::string Simulation<Real>::Advance(double* fastest) {
  const int n = substeps();
  const double start = state_.time, h = params_.dt / n;
  SimParams params = params_;
  params.threads = StepThreads(model_.num_nodes(), params_);
  const StepContext<Real> context{model_, params, wind_, evaluator_};
  const Obstacles obstacles = Obstacles::Of(params_);
  const int passes = params_.self_collision ? CollisionPasses(n) : 1;
  collision_stats_ = {};
  std::string problem;
  for (int pass = 1, done = 0; pass <= passes && problem.empty(); ++pass) {
    if (params_.self_collision) step_start_ = state_;
    const int until = n * pass / passes, from = done;
    for (; done < until; ++done) {
      integrator_->Substep(context, h, &state_);
      PushOutOfObstacles(model_, obstacles, params.threads, &state_);
    }
    // A state already running away is the guard's to roll back, not worth colliding: its swept
    // boxes would cover everything.
    problem = Problem(fastest);
    if (problem.empty() && params_.self_collision) {
      const bool changed =
          self_collision_->Resolve(model_, params, (until - from) * h, step_start_, &state_);
      collision_stats_ += self_collision_->stats();
      if (changed) problem = Problem(fastest);
    }
  }
  state_.time = start + params_.dt;
  ++state_.step;
  return problem;
}

// Self-collision stops a pair where their paths meet, each node by the whole of its approach
// over the interval, while its neighbours that met nothing go on: so nodes must not move much
// further than a spring's length between passes. At the speed of the fastest node at the
// step's start, a pass after every kCollisionReach of the shortest spacing travelled (at most
// one per substep); one pass where nothing is that fast.
template <typename Real>
int Simulation<Real>::CollisionPasses(int substeps) const {
  double fastest_squared = 0;
  const int n = state_.num_nodes();
  const Real *vx = state_.vx.data(), *vy = state_.vy.data(), *vz = state_.vz.data();
#pragma omp simd reduction(max : fastest_squared)
  for (int i = 0; i < n; ++i) {
    const double x = vx[i], y = vy[i], z = vz[i];
    fastest_squared = std::max(fastest_squared, x * x + y * y + z * z);
  }
  const double spacing = std::min(double(model_.dx), double(model_.dy));
  const double passes = std::ceil(std::sqrt(fastest_squared) * params_.dt / (kCollisionReach * spacing));
  return int(std::clamp(passes, 1.0, double(substeps)));
}

template <typename Real>
std::string Simulation<Real>::Problem(double* fastest_out) const {
  // A NaN or infinity anywhere poisons the sum; a blow-up in progress shows as a huge speed
  // or a spring pulled far past its length.
  Real sum = 0, fastest = 0;
  const int n = state_.num_nodes();
  const Real *x = state_.x.data(), *y = state_.y.data(), *z = state_.z.data();
  const Real *vx = state_.vx.data(), *vy = state_.vy.data(), *vz = state_.vz.data();
#pragma omp simd reduction(+ : sum) reduction(max : fastest)
  for (int i = 0; i < n; ++i) {
    sum += x[i] + y[i] + z[i] + vx[i] + vy[i] + vz[i];
    fastest = std::max(fastest, std::max(std::abs(vx[i]), std::max(std::abs(vy[i]), std::abs(vz[i]))));
  }
  if (fastest_out != nullptr) *fastest_out = double(fastest);
  if (!std::isfinite(sum)) return "non-finite positions or velocities";
  if (fastest >= Real(kRunawaySpeed)) return Format("a node at %.3g m/s", fastest);
  const Real stretch_squared = LargestStretchSquared(model_, state_);
  if (stretch_squared >= Real(kRunawayStretch * kRunawayStretch)) {
    return Format("a spring stretched to %.3g times its length", std::sqrt(stretch_squared));
  }
  return "";
}

// Back to the checkpoint, then redo the lost steps more carefully until they come out sound.
template <typename Real>
void Simulation<Real>::Recover(const std::string& problem) {
  const int64_t target = state_.step;
  const double target_time = state_.time;
  GuardEvent event;
  event.step = target;
  event.problem = problem + " with " + IntegratorName(params_.integrator);
  good_steps_ = 0;
  while (true) {
    ++recoveries_;
    if (!Escalate(target - checkpoint_.step, &event)) {  // nothing left to try: a fresh flag
      state_.step = target;
      state_.time = target_time;
      RestartFlag();
      break;
    }
    state_ = checkpoint_;
    integrator_->Reset();
    std::string again;
    while (again.empty() && state_.step < target) again = Advance();
    if (again.empty()) {
      state_.time = target_time;
      break;
    }
  }
  last_event_ = event;
}

// The next measure: twice the substeps; past kMaxGuardFactor a stable integrator. Returns
// false when there is none left (the integrator is already unconditionally stable).
template <typename Real>
bool Simulation<Real>::Escalate(int64_t lost, GuardEvent* event) {
  const std::string redo = "redid " + std::to_string(lost) + " steps from the checkpoint";
  if (guard_factor_ < kMaxGuardFactor) {
    guard_factor_ *= 2;
    event->action = redo + " at " + std::to_string(guard_factor_) + "x the substeps";
    return true;
  }
  guard_factor_ = 1;
  const FrequencyBound bound = EstimateFrequencyBound(model_, AirFriction(params_));
  if (std::isfinite(integrator_->StableStep(bound))) {
    event->action = "switched from " + IntegratorName(params_.integrator) + " to " +
                    IntegratorName(kStableFallback) + " and " + redo;
    params_.integrator = kStableFallback;
    ChooseIntegrator();
    return true;
  }
  event->action = "restarted the flag at rest";
  return false;
}

template class Simulation<float>;
template class Simulation<double>;

}  // namespace flagsim::sim
