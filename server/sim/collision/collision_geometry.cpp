#include "server/sim/collision/collision_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace flagsim::sim {
namespace {

double Clamp01(double value) { return std::clamp(value, 0.0, 1.0); }

/// Bisection stops after kBisections halvings of a bracket (the unit interval to 2^-52), or
/// when the bracket is narrower than kRootWidth of the step.
constexpr int kBisections = 52;
constexpr double kRootWidth = 1e-12;

/// f(t) = c[0] + c[1] t + c[2] t^2 + c[3] t^3.
struct Cubic {
  std::array<double, 4> c{};
  double operator()(double t) const { return c[0] + t * (c[1] + t * (c[2] + t * c[3])); }
};

/// The coplanarity cubic of points a, b, c, d moving linearly: with u = b - a, v = c - a,
/// w = d - a, each u0 + t du, f(t) = (u x v) . w expands term by term in t.
Cubic CoplanarityCubic(const Primitives& points) {
  const Point u0 = points.start[1] - points.start[0], v0 = points.start[2] - points.start[0],
              w0 = points.start[3] - points.start[0];
  const Point du = points.end[1] - points.end[0] - u0, dv = points.end[2] - points.end[0] - v0,
              dw = points.end[3] - points.end[0] - w0;
  const Point uv = u0.cross(v0), mixed = du.cross(v0) + u0.cross(dv), dudv = du.cross(dv);
  return {{uv.dot(w0), mixed.dot(w0) + uv.dot(dw), dudv.dot(w0) + mixed.dot(dw), dudv.dot(dw)}};
}

/// The roots of f in [0, 1], ascending, at most three. Between consecutive roots of f' (and 0,
/// 1) f is monotone, so each bracket with a sign change holds exactly one root.
int RootsInUnitInterval(const Cubic& f, std::array<double, 3>* roots) {
  std::array<double, 4> breaks{0.0, 1.0, 1.0, 1.0};
  int count = 1;
  const double a = 3 * f.c[3], b = 2 * f.c[2], c = f.c[1];  // f'(t) = a t^2 + b t + c
  const auto add_break = [&](double t) {
    if (t > 0 && t < 1) breaks[count++] = t;
  };
  if (a != 0) {
    const double discriminant = b * b - 4 * a * c;
    if (discriminant >= 0) {
      const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));  // no cancellation
      if (q != 0) add_break(c / q);
      add_break(q / a);
    }
  } else if (b != 0) {
    add_break(-c / b);
  }
  if (count == 3 && breaks[1] > breaks[2]) std::swap(breaks[1], breaks[2]);
  breaks[count++] = 1.0;
  int found = 0;
  if (f(0.0) == 0) (*roots)[found++] = 0.0;
  for (int i = 0; i + 1 < count && found < 3; ++i) {
    double lo = breaks[i], hi = breaks[i + 1];
    double f_lo = f(lo);
    const double f_hi = f(hi);
    if (f_hi == 0) {
      if (hi > 0) (*roots)[found++] = hi;
      continue;
    }
    if (f_lo == 0 || (f_lo < 0) == (f_hi < 0)) continue;
    for (int iteration = 0; iteration < kBisections && hi - lo > kRootWidth; ++iteration) {
      const double mid = 0.5 * (lo + hi), f_mid = f(mid);
      if ((f_mid < 0) == (f_lo < 0)) {
        lo = mid;
        f_lo = f_mid;
      } else {
        hi = mid;
      }
    }
    (*roots)[found++] = hi;  // the side after the crossing: the contact is not missed
  }
  return found;
}

double PointTriangleDistance(const std::array<Point, 4>& p) {
  const Eigen::Vector3d w = ClosestOnTriangle(p[0], p[1], p[2], p[3]);
  return (p[0] - (w[0] * p[1] + w[1] * p[2] + w[2] * p[3])).norm();
}

double EdgeEdgeDistance(const std::array<Point, 4>& p) {
  const SegmentParameters closest = ClosestOnSegments(p[0], p[1], p[2], p[3]);
  return ((p[0] + closest.s * (p[1] - p[0])) - (p[2] + closest.t * (p[3] - p[2]))).norm();
}

/// True when f has no root in [0, 1] by its Bernstein coefficients: a cubic on [0, 1] lies
/// within the hull of b0 .. b3, so if they share a strict sign, so does f. Most pairs that are
/// never coplanar during the step stop here.
bool SurelyNoRoot(const Cubic& f) {
  const double b0 = f.c[0], b1 = b0 + f.c[1] / 3, b2 = b1 + (f.c[1] + f.c[2]) / 3,
               b3 = f.c[0] + f.c[1] + f.c[2] + f.c[3];
  return (b0 > 0 && b1 > 0 && b2 > 0 && b3 > 0) || (b0 < 0 && b1 < 0 && b2 < 0 && b3 < 0);
}

template <typename Distance>
std::optional<double> FirstContact(const Primitives& points, double tolerance, Distance distance) {
  const Cubic f = CoplanarityCubic(points);
  if (SurelyNoRoot(f)) return std::nullopt;
  std::array<double, 3> roots{};
  const int count = RootsInUnitInterval(f, &roots);
  for (int i = 0; i < count; ++i) {
    if (distance(points.At(roots[i])) < tolerance) return roots[i];
  }
  return std::nullopt;
}

}  // namespace

// Voronoi regions of the triangle: a vertex, an edge or the face, tested in that order.
Eigen::Vector3d ClosestOnTriangle(const Point& p, const Point& a, const Point& b, const Point& c) {
  const Point ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Point bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Point cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double scale = 1 / (va + vb + vc), v = vb * scale, w = vc * scale;
  return {1 - v - w, v, w};
}

// Minimise |p0 + s d1 - q0 - t d2|^2 over the unit square: the unconstrained s, clamped, then
// the best t for it, clamped, then s again for a clamped t.
SegmentParameters ClosestOnSegments(const Point& p0, const Point& p1, const Point& q0, const Point& q1) {
  constexpr double kDegenerate = 1e-30;  // m^2: a segment this short is a point
  const Point d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  if (a <= kDegenerate && e <= kDegenerate) return {0, 0};
  if (a <= kDegenerate) return {0, Clamp01(f / e)};
  const double c = d1.dot(r);
  if (e <= kDegenerate) return {Clamp01(-c / a), 0};
  const double b = d1.dot(d2), denominator = a * e - b * b;
  double s = denominator > 0 ? Clamp01((b * f - c * e) / denominator) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = Clamp01(-c / a);
  } else if (t > 1) {
    t = 1;
    s = Clamp01((b - c) / a);
  }
  return {s, t};
}

std::array<Point, 4> Primitives::At(double t) const {
  std::array<Point, 4> points;
  for (int i = 0; i < 4; ++i) points[i] = start[i] + t * (end[i] - start[i]);
  return points;
}

std::optional<double> PointTriangleContact(const Primitives& points, double tolerance) {
  return FirstContact(points, tolerance, PointTriangleDistance);
}

std::optional<double> EdgeEdgeContact(const Primitives& points, double tolerance) {
  return FirstContact(points, tolerance, EdgeEdgeDistance);
}

}  // namespace flagsim::sim
