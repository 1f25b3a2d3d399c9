#include "server/sim/collision/normal_cone.hpp"

#include <algorithm>
#include <cmath>

#include "server/sim/collision/lane_layout.hpp"

namespace flagsim::sim {
namespace {

double HalfAngle(const NormalCone& cone) { return std::atan2(cone.sin_half, cone.cos_half); }

}  // namespace

// Two cones with axes a and b, beta apart, and half-angles ta and tb:
//   a holds b when beta + tb <= ta, and b holds a when beta + ta <= tb: the union is the wider;
//   else the union's rim touches both cones' far rims in the plane of the axes: its half-angle
//   is t = (beta + ta + tb) / 2, and its axis is a turned towards b by t - ta in that plane.
// Narrow only when t is under 90 degrees (a narrow cone holds no pair of opposite directions).
// Beta by atan2 of |a x b| and a . b: accurate at every angle, where acos(a . b) loses half the
// digits of an angle near 0.
NormalCone NormalCone::UnionByAngles(const NormalCone& a, const NormalCone& b) {
  const NormalCone open{a.axis};
  if (!a.Narrow() || !b.Narrow()) return open;
  const double ta = HalfAngle(a), tb = HalfAngle(b);
  const double beta = std::atan2(a.axis.cross(b.axis).norm(), a.axis.dot(b.axis));
  if (beta + tb <= ta) return a;
  if (beta + ta <= tb) return b;
  const double t = (beta + ta + tb) / 2;
  if (t >= M_PI / 2) return open;
  // The unit vector square to a in the plane of a and b (beta is over 0 here, under 180 degrees).
  const Point towards_b = (b.axis - a.axis.dot(b.axis) * a.axis).normalized();
  return {std::cos(t - ta) * a.axis + std::sin(t - ta) * towards_b, std::cos(t), std::sin(t)};
}

// UnionByAngles' tests in cosines and sines: beta between the axes, ta and tb the half-angles.
// x holds y when beta + ty <= tx: as beta + ty < 270 degrees and tx < 90, cosines decide. The
// angles add by cos(x + y) = cx cy - sx sy and sin(x + y) = sx cy + cx sy: no inverse
// trigonometry.
//
// Two narrow cones are narrow together when one holds the other, or else when s = beta + ta + tb
// is under 180 degrees (sin s > 0).
bool NormalCone::NarrowCones(const NormalCone& a, const NormalCone& b) {
  const double cb = std::clamp(a.axis.dot(b.axis), -1.0, 1.0), sb = std::sqrt((1 - cb) * (1 + cb));
  const double c1 = cb * a.cos_half - sb * a.sin_half, s1 = sb * a.cos_half + cb * a.sin_half;  // beta + ta
  if (cb * b.cos_half - sb * b.sin_half >= a.cos_half) return true;                             // a holds b
  if (c1 >= b.cos_half) return true;                                                            // b holds a
  return s1 * b.cos_half + c1 * b.sin_half > 0;
}

NormalCone NormalCone::Union(const NormalCone& a, const NormalCone& b) {
  ConeLanes first, second;
  first.Set(0, a);
  second.Set(0, b);
  return ConeLanes::Union(first, second).Cone(0);
}

// UnionByAngles in cosines and sines, as in NarrowCones: if one cone holds the other, the union
// is that one; else its half-angle is s / 2, narrow only when s is under 180 degrees, and its
// axis turns from a's towards b's by s / 2 - ta: it is sin(beta - turn) a + sin(turn) b over
// sin(beta), its length (as in spherical interpolation). Halved by cos^2(s / 2) = (1 + cos s) / 2:
// square roots only. Every case is worked out in every lane and the lane's own picked, so that
// the loop is a run of vector instructions.
ConeLanes ConeLanes::Union(const ConeLanes& a, const ConeLanes& b) {
  ConeLanes out;
#pragma omp simd
  for (int i = 0; i < kLanes; ++i) {
    const double ac = a.cos_half[i], as = a.sin_half[i], bc = b.cos_half[i], bs = b.sin_half[i];
    const double cb = std::clamp(a.x[i] * b.x[i] + a.y[i] * b.y[i] + a.z[i] * b.z[i], -1.0, 1.0);
    const double sb = std::sqrt((1 - cb) * (1 + cb));
    // Bitwise & : no branches in the loop.
    const bool narrow = (ac > 0) & (bc > 0);
    const double c1 = cb * ac - sb * as, s1 = sb * ac + cb * as;  // beta + ta
    const bool a_holds = narrow & (cb * bc - sb * bs >= ac);
    const bool b_holds = narrow & !a_holds & (c1 >= bc);
    const double cos_s = c1 * bc - s1 * bs, sin_s = s1 * bc + c1 * bs;
    const bool joined = narrow & !a_holds & !b_holds & (sin_s > 0);
    const double ch = std::sqrt(std::max(0.0, (1 + cos_s) / 2)),
                 sh = std::sqrt(std::max(0.0, (1 - cos_s) / 2));
    const double st = sh * ac - ch * as, ct = ch * ac + sh * as;
    const double wa = sb * ct - cb * st;
    const double jx = (wa * a.x[i] + st * b.x[i]) / sb, jy = (wa * a.y[i] + st * b.y[i]) / sb,
                 jz = (wa * a.z[i] + st * b.z[i]) / sb;
    // Else open (any direction), about a's axis.
    out.x[i] = a_holds ? a.x[i] : b_holds ? b.x[i] : joined ? jx : a.x[i];
    out.y[i] = a_holds ? a.y[i] : b_holds ? b.y[i] : joined ? jy : a.y[i];
    out.z[i] = a_holds ? a.z[i] : b_holds ? b.z[i] : joined ? jz : a.z[i];
    out.cos_half[i] = a_holds ? ac : b_holds ? bc : joined ? ch : -1.0;
    out.sin_half[i] = a_holds ? as : b_holds ? bs : joined ? sh : 0.0;
  }
  return out;
}

}  // namespace flagsim::sim
