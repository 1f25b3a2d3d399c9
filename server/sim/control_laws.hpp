// Control laws: how a control moves from one keyframe's value to the next (the seed's
// keyframe animation). Each law maps the segment's fraction s in [0, 1] and the values at
// its keys (and, for the cubic, the keys around it) to a value; all are exact at the keys.
//   step     a until the next key, then b                      (discontinuous by design)
//   linear   a + (b - a) s                                      (C0)
//   smooth   a + (b - a) (3 s^2 - 2 s^3): eases out of a and in to b, zero rate at both (C1)
//   cubic    cubic Hermite through the keys with Catmull-Rom rates from the neighbouring keys,
//            (p_{i+1} - p_{i-1}) / (t_{i+1} - t_{i-1}) for uneven key times (C1 across keys)
// Wind turns by angle, not componentwise: its direction moves along the great circle between
// the keys' directions while its speed follows the law, so a wind swinging from east to west
// does not die down on the way.
#pragma once

#include <string>
#include <vector>

#include "server/sim/vec3.hpp"

namespace flagsim::sim {

enum class ControlLaw { kStep, kLinear, kSmooth, kCubic };

/// Names as commands and scene files spell them, in ControlLaw order.
const std::vector<std::string>& ControlLawNames();

/// One scalar control at time t inside the segment (t0, t1) of keys with values (v0, v1); the
/// cubic also reads the keys before and after, (t_before, v_before) and (t_after, v_after),
/// which the caller sets to the segment's own ends where there is no such key.
struct Segment {
  double t0 = 0, t1 = 1;
  double v0 = 0, v1 = 0;
  double t_before = 0, v_before = 0;
  double t_after = 1, v_after = 0;
};

/// The law's value at time t in [t0, t1].
double Interpolate(ControlLaw law, const Segment& segment, double t);

/// Bounds on the values the law takes over the whole segment: the keys' values, and for the
/// cubic its overshoot. The cubic Hermite segment is the Bezier curve with control values
/// v0, v0 + m0/3, v1 - m1/3, v1 (m the rates times the span), and lies within their range.
struct ValueRange {
  double low = 0, high = 0;
};
ValueRange RangeOver(ControlLaw law, const Segment& segment);

/// The direction a fraction s in [0, 1] of the way from unit vector `from` to unit vector `to`
/// along the great circle between them (spherical linear interpolation). Opposite directions
/// turn through the horizontal plane (about the vertical axis, or about x if they are vertical).
Vec3 Slerp(const Vec3& from, const Vec3& to, double s);

}  // namespace flagsim::sim
