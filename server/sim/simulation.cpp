#include "simulation.hpp"

#include <algorithm>
#include <cmath>

namespace flagsim::sim {
namespace {

bool GridChanged(const SimParams& a, const SimParams& b) {
  return a.cols != b.cols || a.rows != b.rows || a.width != b.width || a.height != b.height ||
         a.mass != b.mass || a.pole_height != b.pole_height;
}

constexpr int kMaxSubsteps = 1 << 16;

}  // namespace

template <typename Real>
Simulation<Real>::Simulation(const SimParams& params, const WindSettings& wind, uint64_t seed)
    : params_(params), wind_(wind, seed) {
  Rebuild();
  state_ = RestState(model_);
  Checkpoint();
}

template <typename Real>
void Simulation<Real>::Rebuild() {
  model_ = BuildClothModel<Real>(params_);
  integrator_ = MakeIntegrator<Real>(params_.integrator);
  const FrequencyBound bound = EstimateFrequencyBound(model_, AirFriction(params_));
  const double stable = kSafety * integrator_->StableStep(bound);
  const double needed = std::ceil(params_.dt / stable);
  substeps_ = static_cast<int>(std::clamp(needed, 1.0, double(kMaxSubsteps)));
}

template <typename Real>
void Simulation<Real>::SetParams(const SimParams& params) {
  const bool regrid = GridChanged(params, params_);
  params_ = params;
  Rebuild();
  if (regrid) RestartFlag();
  Checkpoint();
}

template <typename Real>
void Simulation<Real>::SetWind(const WindSettings& wind) {
  wind_.Set(wind, state_.time);
  integrator_->Reset();
  Checkpoint();  // a rollback must not replay earlier steps under the new wind
}

template <typename Real>
void Simulation<Real>::RestartFlag() {
  const double time = state_.time;
  const int64_t step = state_.step;
  state_ = RestState(model_);
  state_.time = time;
  state_.step = step;
  integrator_->Reset();
  Checkpoint();
}

template <typename Real>
void Simulation<Real>::Step() {
  if (state_.step % kCheckpointInterval == 0) Checkpoint();
  Advance();
  if (!StateIsSound()) {
    Recover();
  } else if (guard_factor_ > 1 && ++good_steps_ >= 64 * kCheckpointInterval) {
    guard_factor_ /= 2;  // the trouble has passed: relax towards the stability limit
    good_steps_ = 0;
  }
}

template <typename Real>
void Simulation<Real>::Advance() {
  const int n = substeps();
  const double start = state_.time, h = params_.dt / n;
  const StepContext<Real> context{model_, params_, wind_, evaluator_};
  for (int i = 0; i < n; ++i) integrator_->Substep(context, h, &state_);
  state_.time = start + params_.dt;
  ++state_.step;
}

template <typename Real>
bool Simulation<Real>::StateIsSound() const {
  // A NaN or infinity anywhere poisons the sum; a blow-up in progress shows as a huge speed.
  Real sum = 0, fastest = 0;
  const int n = state_.num_nodes();
  const Real *x = state_.x.data(), *y = state_.y.data(), *z = state_.z.data();
  const Real *vx = state_.vx.data(), *vy = state_.vy.data(), *vz = state_.vz.data();
#pragma omp simd reduction(+ : sum) reduction(max : fastest)
  for (int i = 0; i < n; ++i) {
    sum += x[i] + y[i] + z[i] + vx[i] + vy[i] + vz[i];
    fastest = std::max(fastest, std::max(std::abs(vx[i]), std::max(std::abs(vy[i]), std::abs(vz[i]))));
  }
  return std::isfinite(sum) && fastest < Real(kRunawaySpeed);
}

template <typename Real>
void Simulation<Real>::Recover() {
  const int64_t target = state_.step;
  const double target_time = state_.time;
  good_steps_ = 0;
  while (true) {
    ++recoveries_;
    if (guard_factor_ >= kMaxGuardFactor) {  // no step is small enough: start the flag afresh
      guard_factor_ = 1;
      state_ = RestState(model_);
      state_.step = target;
      state_.time = target_time;
      Checkpoint();
      return;
    }
    guard_factor_ *= 2;
    state_ = checkpoint_;
    integrator_->Reset();
    bool sound = true;
    while (sound && state_.step < target) {
      Advance();
      sound = StateIsSound();
    }
    if (sound) return;
  }
}

template class Simulation<float>;
template class Simulation<double>;

}  // namespace flagsim::sim
