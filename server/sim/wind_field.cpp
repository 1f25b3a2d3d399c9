#include "server/sim/wind_field.hpp"

#include <cmath>

namespace flagsim::sim {
namespace {

/// splitmix64's finaliser: a well-mixed 64-bit hash of one integer.
uint64_t Mix(uint64_t value) {
  value += 0x9e3779b97f4a7c15ull;
  value = (value ^ (value >> 30)) * 0xbf58476d1ce4e5b9ull;
  value = (value ^ (value >> 27)) * 0x94d049bb133111ebull;
  return value ^ (value >> 31);
}

double LatticeValue(uint64_t seed, int64_t i) {
  const uint64_t bits = Mix(seed ^ Mix(static_cast<uint64_t>(i)));
  return double(bits >> 11) * (2.0 / 9007199254740992.0) - 1.0;  // 53 bits -> [-1, 1)
}

}  // namespace

// The lattice repeats every 2^52 cells, far beyond any session (a smaller |u| is left exactly as
// it is), so that every finite u's cell fits int64_t. A u that is not finite (a state gone wrong,
// which the guard catches) has no noise.
double NoiseCursor::operator()(double u) {
  if (!(std::fabs(u) < 0x1p52)) {
    if (!std::isfinite(u)) return 0;
    u = std::fmod(u, 0x1p52);
  }
  const double cell = std::floor(u);
  const double f = u - cell;
  const double blend = f * f * f * (f * (f * 6 - 15) + 10);  // C2-continuous
  const int64_t i = static_cast<int64_t>(cell);
  if (!valid_ || i != cell_) {
    a_ = LatticeValue(seed_, i);
    b_ = LatticeValue(seed_, i + 1);
    cell_ = i;
    valid_ = true;
  }
  return a_ + (b_ - a_) * blend;
}

WindField::WindField(const WindSettings& settings, uint64_t seed)
    : from_(settings), to_(settings), seed_(seed) {}

WindField::WindField(const WindFieldState& state)
    : from_(state.from),
      to_(state.to),
      ramp_start_(state.ramp_start),
      carried_(state.carried),
      seed_(state.seed) {}

void WindField::Set(const WindSettings& settings, double now) {
  carried_ = Carried(now);
  from_.velocity = Mean(now);
  from_.gust = Gust(now);
  to_ = settings;
  ramp_start_ = now;
}

double WindField::RampFraction(double t) const {
  if (to_.ramp_time <= 0) return 1.0;
  const double fraction = (t - ramp_start_) / to_.ramp_time;
  return fraction < 0 ? 0.0 : fraction > 1 ? 1.0 : fraction;
}

Vec3 WindField::Mean(double t) const {
  const double a = RampFraction(t);
  Vec3 mean;
  for (int k = 0; k < 3; ++k) mean[k] = from_.velocity[k] + a * (to_.velocity[k] - from_.velocity[k]);
  return mean;
}

double WindField::Gust(double t) const {
  const double a = RampFraction(t);
  return from_.gust + a * (to_.gust - from_.gust);
}

// carried(t0) + integral from t0 to t of |from| + a(tau) (|to| - |from|), a the ramp fraction
// (tau - t0) / T, clamped to [0, 1]: its integral is (t - t0)^2 / 2T while ramping, then
// T / 2 + (t - t0 - T).
double WindField::Carried(double t) const {
  const double elapsed = t - ramp_start_, ramp = to_.ramp_time;
  const double from = Length(from_.velocity), to = Length(to_.velocity);
  double ramped = elapsed;  // the integral of a
  if (elapsed <= 0) {
    ramped = 0;
  } else if (elapsed < ramp) {
    ramped = elapsed * elapsed / (2 * ramp);
  } else if (ramp > 0) {
    ramped = elapsed - ramp / 2;
  }
  return carried_ + from * elapsed + (to - from) * ramped;
}

Vec3 WindField::At(double t, double s) const {
  Vec3 wind;
  Along(t, &s, 1, &wind);
  return wind;
}

void WindField::Along(double t, const double* s, int count, Vec3* out) const {
  const Vec3 mean = Mean(t);
  const double amplitude = Gust(t) * Length(mean);
  const double carried = amplitude == 0 ? 0 : Carried(t);
  NoiseCursor noise[3] = {NoiseCursor(seed_ + 0x51ed27), NoiseCursor(seed_ + 0x51ed27 * 2),
                          NoiseCursor(seed_ + 0x51ed27 * 3)};
  for (int j = 0; j < count; ++j) {
    out[j] = mean;
    if (amplitude == 0) continue;
    const double u = (carried - s[j]) / kGustLength;
    for (int k = 0; k < 3; ++k) out[j][k] += amplitude * noise[k](u);
  }
}

}  // namespace flagsim::sim
