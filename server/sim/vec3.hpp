// Small 3-vectors of doubles for the controls (wind, camera, key directions), and the few
// operations on them. The cloth's own arrays are float or double per node (node_vectors.hpp);
// these are single values, kept as plain arrays so that messages and scene files copy them as
// they are.
#pragma once

#include <array>
#include <cmath>

namespace flagsim::sim {

using Vec3 = std::array<double, 3>;

/// a . b = a_x b_x + a_y b_y + a_z b_z, summed in that order.
inline double Dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// a x b.
inline Vec3 Cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// |v| = sqrt(v . v).
inline double Length(const Vec3& v) { return std::sqrt(Dot(v, v)); }

/// v f.
inline Vec3 Scaled(const Vec3& v, double factor) { return {v[0] * factor, v[1] * factor, v[2] * factor}; }

}  // namespace flagsim::sim
