// An independent count of crossing triangle pairs, for tests and benchmarks: it shares no code
// with the collision handling it checks.
//
// Two triangles that share no corner cross when an edge of one passes through the other. A
// segment pq passes through triangle abc when p and q lie on opposite sides of abc's plane and
// the line pq passes inside its three edges: orient(a, b, c, p) and orient(a, b, c, q) differ in
// sign, and orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a) agree. Each orientation
// is a determinant in long double with a bound on its rounding error; a sign within the bound
// is taken as zero, and a zero counts as touching: an uncertain case is reported as a crossing,
// never hidden. A segment in the triangle's plane is decided in that plane.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

namespace flagsim::lab {

using Point3 = std::array<long double, 3>;

/// The sign of det[b - a, c - a, d - a]: +1, -1, or 0 when rounding could hide it.
inline int Orientation(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  long double m[3][3], magnitude = 0;
  for (int k = 0; k < 3; ++k) {
    m[0][k] = b[k] - a[k];
    m[1][k] = c[k] - a[k];
    m[2][k] = d[k] - a[k];
  }
  const long double terms[6] = {m[0][0] * m[1][1] * m[2][2],  m[0][1] * m[1][2] * m[2][0],
                                m[0][2] * m[1][0] * m[2][1],  -m[0][2] * m[1][1] * m[2][0],
                                -m[0][1] * m[1][0] * m[2][2], -m[0][0] * m[1][2] * m[2][1]};
  long double det = 0;
  for (long double term : terms) {
    det += term;
    magnitude += std::fabs(term);
  }
  // The inputs are floats, their differences exact in long double to a relative 2^-64; the
  // products and the sum add a few more roundings: 64 ulps of the terms' magnitude is ample.
  const long double bound = 64 * magnitude * 5.42e-20L;
  return det > bound ? 1 : det < -bound ? -1 : 0;
}

using Point2 = std::array<long double, 2>;

/// The sign of det[b - a, c - a] in the plane, 0 when rounding could hide it.
inline int Orientation(const Point2& a, const Point2& b, const Point2& c) {
  const long double first = (b[0] - a[0]) * (c[1] - a[1]), second = (b[1] - a[1]) * (c[0] - a[0]);
  const long double det = first - second, bound = 16 * (std::fabs(first) + std::fabs(second)) * 5.42e-20L;
  return det > bound ? 1 : det < -bound ? -1 : 0;
}

/// Whether closed segments pq and ab in the plane meet; collinear ones by their extents.
inline bool SegmentsMeet(const Point2& p, const Point2& q, const Point2& a, const Point2& b) {
  const int o1 = Orientation(p, q, a), o2 = Orientation(p, q, b), o3 = Orientation(a, b, p),
            o4 = Orientation(a, b, q);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  const auto within = [](const Point2& s, const Point2& t, const Point2& r) {  // r on st's line
    return std::min(s[0], t[0]) <= r[0] && r[0] <= std::max(s[0], t[0]) && std::min(s[1], t[1]) <= r[1] &&
           r[1] <= std::max(s[1], t[1]);
  };
  return (o1 == 0 && within(p, q, a)) || (o2 == 0 && within(p, q, b)) || (o3 == 0 && within(a, b, p)) ||
         (o4 == 0 && within(a, b, q));
}

/// Segment pq and triangle abc in one plane: dropped to the two coordinates in which the
/// triangle is largest, they meet if pq meets an edge or p lies inside.
inline bool CoplanarSegmentMeetsTriangle(const Point3& p, const Point3& q, const Point3& a, const Point3& b,
                                         const Point3& c) {
  const long double n[3] = {(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
                            (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
                            (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])};
  const int drop = std::fabs(n[0]) >= std::fabs(n[1]) && std::fabs(n[0]) >= std::fabs(n[2]) ? 0
                   : std::fabs(n[1]) >= std::fabs(n[2])                                     ? 1
                                                                                            : 2;
  const int u = drop == 0 ? 1 : 0, v = drop == 2 ? 1 : 2;
  const auto flat = [&](const Point3& r) { return Point2{r[u], r[v]}; };
  const Point2 p2 = flat(p), q2 = flat(q), a2 = flat(a), b2 = flat(b), c2 = flat(c);
  if (SegmentsMeet(p2, q2, a2, b2) || SegmentsMeet(p2, q2, b2, c2) || SegmentsMeet(p2, q2, c2, a2))
    return true;
  const int o0 = Orientation(a2, b2, p2), o1 = Orientation(b2, c2, p2), o2 = Orientation(c2, a2, p2);
  return (o0 >= 0 && o1 >= 0 && o2 >= 0) || (o0 <= 0 && o1 <= 0 && o2 <= 0);
}

/// True when segment pq passes through or touches triangle abc (see above).
inline bool SegmentCrossesTriangle(const Point3& p, const Point3& q, const Point3& a, const Point3& b,
                                   const Point3& c) {
  const int sp = Orientation(a, b, c, p), sq = Orientation(a, b, c, q);
  if (sp != 0 && sp == sq) return false;
  if (sp == 0 && sq == 0) return CoplanarSegmentMeetsTriangle(p, q, a, b, c);
  const int e0 = Orientation(p, q, a, b), e1 = Orientation(p, q, b, c), e2 = Orientation(p, q, c, a);
  const bool has_positive = e0 > 0 || e1 > 0 || e2 > 0, has_negative = e0 < 0 || e1 < 0 || e2 < 0;
  return !(has_positive && has_negative);
}

/// Pairs of triangles with no corner in common that cross, over a mesh of `triangles` (node
/// indices) on node positions x, y, z. Candidates are pruned by box overlap (sorted along x).
template <typename Real>
int CrossingTrianglePairs(const std::vector<std::array<int, 3>>& triangles, const std::vector<Real>& x,
                          const std::vector<Real>& y, const std::vector<Real>& z) {
  const int count = int(triangles.size());
  std::vector<std::array<long double, 6>> box(count);  // lo x, y, z, hi x, y, z
  for (int t = 0; t < count; ++t) {
    box[t] = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    for (int v : triangles[t]) {
      const long double p[3] = {x[v], y[v], z[v]};
      for (int k = 0; k < 3; ++k) {
        box[t][k] = std::min(box[t][k], p[k]);
        box[t][k + 3] = std::max(box[t][k + 3], p[k]);
      }
    }
  }
  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return box[a][0] < box[b][0]; });
  const auto point = [&](int v) { return Point3{x[v], y[v], z[v]}; };
  int crossings = 0;
  for (int i = 0; i < count; ++i) {
    const int s = order[i];
    for (int j = i + 1; j < count && box[order[j]][0] <= box[s][3]; ++j) {
      const int t = order[j];
      if (box[t][1] > box[s][4] || box[s][1] > box[t][4] || box[t][2] > box[s][5] || box[s][2] > box[t][5])
        continue;
      const std::array<int, 3>&a = triangles[s], &b = triangles[t];
      bool shared = false;
      for (int u : a) shared = shared || u == b[0] || u == b[1] || u == b[2];
      if (shared) continue;
      bool cross = false;
      for (int k = 0; k < 3 && !cross; ++k) {
        cross =
            SegmentCrossesTriangle(point(a[k]), point(a[(k + 1) % 3]), point(b[0]), point(b[1]),
                                   point(b[2])) ||
            SegmentCrossesTriangle(point(b[k]), point(b[(k + 1) % 3]), point(a[0]), point(a[1]), point(a[2]));
      }
      crossings += cross;
    }
  }
  return crossings;
}

}  // namespace flagsim::lab
