#include "server/sim/control_laws.hpp"

#include <algorithm>
#include <cmath>

namespace flagsim::sim {
namespace {

/// v / |v|.
Vec3 Normalized(const Vec3& v) {
  const double length = Length(v);
  return {v[0] / length, v[1] / length, v[2] / length};
}

/// `span` times the rate at a key of the Catmull-Rom spline through its neighbours (ta, va) and
/// (tb, vb): (vb - va) span / (tb - ta). The neighbours bracket the segment, so span / (tb - ta)
/// is at most 1 and is taken first: keys however close (1e-307 s apart) give no overflow, where
/// the rate alone would be infinite and the cubic NaN.
double ScaledCatmullRomRate(double span, double ta, double va, double tb, double vb) {
  return tb > ta ? (vb - va) * (span / (tb - ta)) : 0.0;
}

/// The cubic's end rates times the segment's span: Catmull-Rom from the neighbouring keys.
void CubicRates(const Segment& g, double* m0, double* m1) {
  const double span = g.t1 - g.t0;
  *m0 = ScaledCatmullRomRate(span, g.t_before, g.v_before, g.t1, g.v1);
  *m1 = ScaledCatmullRomRate(span, g.t0, g.v0, g.t_after, g.v_after);
}

}  // namespace

const std::vector<std::string>& ControlLawNames() {
  static const std::vector<std::string> names = {"step", "linear", "smooth", "cubic"};
  return names;
}

double Interpolate(ControlLaw law, const Segment& g, double t) {
  const double span = g.t1 - g.t0;
  const double s = span > 0 ? std::clamp((t - g.t0) / span, 0.0, 1.0) : 1.0;
  switch (law) {
    case ControlLaw::kStep:
      return s < 1 ? g.v0 : g.v1;
    case ControlLaw::kLinear:
      return g.v0 + (g.v1 - g.v0) * s;
    case ControlLaw::kSmooth:
      return g.v0 + (g.v1 - g.v0) * s * s * (3 - 2 * s);
    case ControlLaw::kCubic: {
      // Hermite basis on [0, 1] with the rates scaled to the segment's length.
      double m0 = 0, m1 = 0;
      CubicRates(g, &m0, &m1);
      const double s2 = s * s, s3 = s2 * s;
      return (2 * s3 - 3 * s2 + 1) * g.v0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * g.v1 +
             (s3 - s2) * m1;
    }
  }
  return g.v1;
}

ValueRange RangeOver(ControlLaw law, const Segment& g) {
  ValueRange range{std::min(g.v0, g.v1), std::max(g.v0, g.v1)};
  if (law != ControlLaw::kCubic) return range;  // monotone between the keys
  double m0 = 0, m1 = 0;
  CubicRates(g, &m0, &m1);
  for (const double control : {g.v0 + m0 / 3, g.v1 - m1 / 3}) {
    range.low = std::min(range.low, control);
    range.high = std::max(range.high, control);
  }
  return range;
}

Vec3 Slerp(const Vec3& from, const Vec3& to, double s) {
  const double cosine = std::clamp(Dot(from, to), -1.0, 1.0);
  const double angle = std::acos(cosine);
  if (angle < 1e-9) return to;
  // The axis to turn about, perpendicular to `from`: from x to; for opposite directions, the
  // vertical made perpendicular to `from` (x instead if `from` is vertical).
  Vec3 axis = Cross(from, to);
  if (Dot(axis, axis) < 1e-18) {
    const Vec3 up = std::abs(from[1]) < 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    const double along = Dot(up, from);
    axis = {up[0] - along * from[0], up[1] - along * from[1], up[2] - along * from[2]};
  }
  axis = Normalized(axis);
  // Rodrigues for a vector perpendicular to the axis: from cos(theta) + (axis x from) sin(theta).
  const Vec3 across = Cross(axis, from);
  const double theta = s * angle;
  Vec3 turned;
  for (int k = 0; k < 3; ++k) turned[k] = from[k] * std::cos(theta) + across[k] * std::sin(theta);
  return Normalized(turned);
}

}  // namespace flagsim::sim
