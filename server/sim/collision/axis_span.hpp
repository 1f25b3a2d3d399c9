// What a body covers along an axis: the least and the most of axis . x over its points, or over
// balls about them. Two bodies whose spans are more than `room` apart are parted by a plane
// square to the axis with that room to spare: along a unit axis, farther apart than `room`;
// along an axis of length L, compare with room L (the spans scale with L too). This is the one
// test of "apart along an axis" in the collision code: a patch pair (CollisionCulling::
// Separated), a primitive pair over the step (CollisionCulling::Parted) and at its start
// (self_collision.cpp, along x, y and z).
#pragma once

#include <algorithm>
#include <cmath>

namespace flagsim::sim {

struct AxisSpan {
  double least = INFINITY, most = -INFINITY;  ///< of axis . x; empty to start

  /// Takes in a point at `along` = axis . x.
  void Add(double along) {
    least = std::min(least, along);
    most = std::max(most, along);
  }
  /// Takes in a ball whose centre is at `along` and which reaches `reach` either side of it.
  void Add(double along, double reach) {
    least = std::min(least, along - reach);
    most = std::max(most, along + reach);
  }
  /// This span lies beyond `other`, further along the axis, by more than `room`.
  bool Beyond(const AxisSpan& other, double room) const { return least - other.most > room; }
};

/// Whether either span lies beyond the other by more than `room`.
inline bool Apart(const AxisSpan& a, const AxisSpan& b, double room) {
  return b.Beyond(a, room) || a.Beyond(b, room);
}

}  // namespace flagsim::sim
