// The wind the flag sees: a mean velocity that ramps from one setting to the next in simulated
// time, plus gusts of seeded, smooth noise that travel down the flag with the mean wind.
#pragma once

#include <cstdint>

#include "server/sim/vec3.hpp"

namespace flagsim::sim {

struct WindSettings {
  Vec3 velocity{6.0, 0.0, 1.5};  ///< m/s, world frame
  double gust = 0.2;             ///< gust strength, fraction of |velocity|
  double ramp_time = 0.0;        ///< s, simulated time to reach this setting from the last one
};

/// Everything a WindField is, for checkpoints: the ramp it is on, how far the wind had carried
/// the gusts when the ramp began, and their seed.
struct WindFieldState {
  WindSettings from;      ///< the wind the ramp started from
  WindSettings to;        ///< the wind it goes to
  double ramp_start = 0;  ///< s, simulated time the ramp began
  double carried = 0;     ///< m, WindField::Carried(ramp_start)
  uint64_t seed = 1;      ///< gust noise
};

class WindField {
 public:
  explicit WindField(const WindSettings& settings = {}, uint64_t seed = 1);
  explicit WindField(const WindFieldState& state);

  /// From time `now`, move linearly from the current wind to `settings` over its ramp_time.
  void Set(const WindSettings& settings, double now);

  /// The mean wind at time t (the ramp applied), m/s.
  Vec3 Mean(double t) const;
  /// The gust strength at time t (ramped like the mean).
  double Gust(double t) const;
  /// The wind at time t at distance `s` metres down the flag from the pole (its material
  /// coordinate): Mean(t) + Gust(t) |Mean(t)| N((Carried(t) - s) / kGustLength), where N is
  /// smooth noise in [-1, 1] per component. Frozen turbulence carried by the mean wind.
  Vec3 At(double t, double s) const;
  /// out[j] = At(t, s[j]) for j in [0, count), bit for bit, in less time: what depends on t
  /// alone (the mean, the gusts' size, the distance carried) is computed once, and each lattice
  /// value of the noise once while consecutive points share a lattice cell.
  void Along(double t, const double* s, int count, Vec3* out) const;
  /// m: how far the mean wind has carried the turbulence by time t, the integral of its speed
  /// (|w| t for a wind that never changed). A new setting goes on from where the last one had
  /// carried it, so the gusts never jump when the wind changes, however often it does. Over a
  /// ramp the speed is taken to ramp linearly from the old to the new.
  double Carried(double t) const;

  const WindSettings& target() const { return to_; }
  uint64_t seed() const { return seed_; }
  WindFieldState State() const { return {from_, to_, ramp_start_, carried_, seed_}; }

  static constexpr double kGustLength = 1.5;  ///< m, correlation length of gusts

 private:
  double RampFraction(double t) const;

  WindSettings from_;
  WindSettings to_;
  double ramp_start_ = 0;  ///< s
  double carried_ = 0;     ///< m: Carried(ramp_start_)
  uint64_t seed_;
};

/// Smooth 1D value noise in [-1, 1] (a quintic blend between hashed values at the integers),
/// evaluated at u after u: the hashed values of the last lattice cell are kept, so consecutive
/// u in one cell cost no hashing. Periodic over 2^52 cells; 0 where u is not finite.
class NoiseCursor {
 public:
  explicit NoiseCursor(uint64_t seed) : seed_(seed) {}
  double operator()(double u);

 private:
  uint64_t seed_;
  bool valid_ = false;
  int64_t cell_ = 0;  ///< the lattice cell [cell_, cell_ + 1] that a_ and b_ belong to
  double a_ = 0, b_ = 0;
};

}  // namespace flagsim::sim
