// Distances and first contacts between the cloth's primitives: a point and a triangle, two
// edges. Positions move linearly over a step, x(t) = x0 + t (x1 - x0), t in [0, 1].
//
// Contact along such a path (continuous collision detection, Provot 1997; Bridson, Fedkiw and
// Anderson 2002, section 6.4): the four points are first coplanar where the cubic
//   f(t) = ((x_b - x_a) x (x_c - x_a)) . (x_d - x_a)
// vanishes; a root is a contact if the primitives are then closer than a tolerance. The cubic's
// roots in [0, 1] are bracketed between the roots of f' and found by bisection, which needs no
// starting guess and cannot step out of its bracket.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>

namespace flagsim::sim {

using Point = Eigen::Vector3d;

/// The point of triangle (a, b, c) closest to p, as barycentric weights (w_a, w_b, w_c).
Eigen::Vector3d ClosestOnTriangle(const Point& p, const Point& a, const Point& b, const Point& c);

/// The closest points of segments p0 p1 and q0 q1: p0 + s (p1 - p0) and q0 + t (q1 - q0).
struct SegmentParameters {
  double s = 0, t = 0;
};
SegmentParameters ClosestOnSegments(const Point& p0, const Point& p1, const Point& q0, const Point& q1);

/// The four points of a point-triangle pair (p, a, b, c) or an edge pair (p0, p1, q0, q1),
/// at the start and the end of the step.
struct Primitives {
  std::array<Point, 4> start, end;
  std::array<Point, 4> At(double t) const;
};

/// The first time in [0, 1] at which the point meets the triangle (Primitives: p, a, b, c)
/// within `tolerance` m, if any.
std::optional<double> PointTriangleContact(const Primitives& points, double tolerance);
/// The first time in [0, 1] at which the edges meet (Primitives: p0, p1, q0, q1) within
/// `tolerance` m, if any.
std::optional<double> EdgeEdgeContact(const Primitives& points, double tolerance);

}  // namespace flagsim::sim
