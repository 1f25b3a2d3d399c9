#include "server/sim/normal_cone.hpp"

#include <algorithm>
#include <cmath>

namespace flagsim::sim {
namespace {

/// Two narrow cones' angles summed, in cosines and sines: the angle beta between the axes; the
/// cone that holds the other, if one does; else s = beta + ta + tb. With either cone open, s is
/// reported as 180 degrees.
struct ConeSum {
  const NormalCone* holder = nullptr;
  double cos_beta = 1, sin_beta = 0, cos_s = -1, sin_s = 0;
};

// x holds y when beta + ty <= tx: as beta + ty < 270 degrees and tx < 90, cosines decide. The
// angles add by cos(x + y) = cx cy - sx sy and sin(x + y) = sx cy + cx sy: no inverse
// trigonometry.
ConeSum Sum(const NormalCone& a, const NormalCone& b) {
  ConeSum sum;
  if (!a.Narrow() || !b.Narrow()) return sum;
  const double cb = std::clamp(a.axis.dot(b.axis), -1.0, 1.0), sb = std::sqrt((1 - cb) * (1 + cb));
  sum.cos_beta = cb;
  sum.sin_beta = sb;
  const auto holds = [cb, sb](const NormalCone& x, const NormalCone& y) {
    return cb * y.cos_half - sb * y.sin_half >= x.cos_half;
  };
  sum.holder = holds(a, b) ? &a : holds(b, a) ? &b : nullptr;
  if (sum.holder != nullptr) return sum;
  const double c1 = cb * a.cos_half - sb * a.sin_half, s1 = sb * a.cos_half + cb * a.sin_half;  // beta + ta
  sum.cos_s = c1 * b.cos_half - s1 * b.sin_half;
  sum.sin_s = s1 * b.cos_half + c1 * b.sin_half;
  return sum;
}

}  // namespace

// With beta the angle between the axes and ta, tb the half-angles: if one cone holds the other,
// the union is that one; else its half-angle is s / 2 with s = beta + ta + tb, narrow only when
// s is under 180 degrees, and its axis turns from a's towards b's by s / 2 - ta. Halved by
// cos^2(s / 2) = (1 + cos s) / 2: square roots only.
NormalCone NormalCone::Union(const NormalCone& a, const NormalCone& b) {
  const ConeSum sum = Sum(a, b);
  if (sum.holder != nullptr) return *sum.holder;
  if (sum.sin_s <= 0) return {a.axis};  // s in [180, 360) degrees, or either cone was not narrow
  // s / 2, and the turn s / 2 - ta; the axis is sin(beta - turn) a + sin(turn) b over sin(beta),
  // its length (as in spherical interpolation).
  const double ch = std::sqrt((1 + sum.cos_s) / 2), sh = std::sqrt((1 - sum.cos_s) / 2);
  const double st = sh * a.cos_half - ch * a.sin_half, ct = ch * a.cos_half + sh * a.sin_half;
  const Point axis = (sum.sin_beta * ct - sum.cos_beta * st) * a.axis + st * b.axis;
  return {axis / sum.sin_beta, ch, sh};
}

bool NormalCone::NarrowTogether(const NormalCone& a, const NormalCone& b) {
  const ConeSum sum = Sum(a, b);
  return sum.holder != nullptr ? sum.holder->Narrow() : sum.sin_s > 0;
}

}  // namespace flagsim::sim
