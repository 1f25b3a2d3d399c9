// Something that falls due every 1/rate s of simulated time: STATE, frames, PARAMS in a render.
// Which steps publish is part of the session, not of the machine's speed, so the live server
// and a render share this. The first is due at time 0. A check that comes more than a period
// late (a step longer than the period, a rate raised) does not owe every period it missed:
// one more falls due at the next check, and the schedule goes on from there.
#pragma once

#include <algorithm>

namespace flagsim {

class SimCadence {
 public:
  /// True if something is due at `time` (s, simulated; early by up to `tolerance` s counts),
  /// and then the next is scheduled. Never due at a rate of 0 or below.
  bool Due(double time, double rate, double tolerance = 0) {
    if (rate <= 0 || time + tolerance < next_) return false;
    next_ = std::max(next_ + 1.0 / rate, time);
    return true;
  }

  double next() const { return next_; }  ///< s, simulated: when it is due next

 private:
  double next_ = 0;
};

}  // namespace flagsim
