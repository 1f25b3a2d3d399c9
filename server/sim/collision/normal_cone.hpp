// A cone of directions: the unit vectors within a half-angle theta of a unit axis, carried as
// cos theta and sin theta. A surface whose normals all lie in a narrow cone (theta under 90
// degrees) over a whole step cannot meet itself then (Volino and Magnenat-Thalmann 1994, the
// normal-cone criterion): self-collision culls such regions of the cloth (self_collision.hpp).
#pragma once

#include <array>

#include "server/sim/collision/collision_geometry.hpp"

namespace flagsim::sim {

struct NormalCone {
  Point axis = Point::UnitZ();
  double cos_half = -1, sin_half = 0;  ///< the default: 180 degrees, any direction

  bool Narrow() const { return cos_half > 0; }

  /// The smallest cone holding both (normal_cone.cpp); any direction when that is not narrow.
  static NormalCone Union(const NormalCone& a, const NormalCone& b);
  /// Union(a, b).Narrow(), without the union's axis.
  static bool NarrowTogether(const NormalCone& a, const NormalCone& b) {
    return a.Narrow() && b.Narrow() && NarrowCones(a, b);
  }

 private:
  /// NarrowTogether of two narrow cones.
  static bool NarrowCones(const NormalCone& a, const NormalCone& b);
};

/// kLanes cones side by side, each quantity of them contiguous, so that the unions of kLanes
/// pairs are worked out together by vector instructions (ConeLanes::Union).
struct ConeLanes {
  static constexpr int kLanes = 4;
  std::array<double, kLanes> x{}, y{}, z{}, cos_half{}, sin_half{};

  ConeLanes() { cos_half.fill(-1); }
  NormalCone Cone(int lane) const {
    return {Point(x[lane], y[lane], z[lane]), cos_half[lane], sin_half[lane]};
  }
  void Set(int lane, const NormalCone& cone) {
    x[lane] = cone.axis.x();
    y[lane] = cone.axis.y();
    z[lane] = cone.axis.z();
    cos_half[lane] = cone.cos_half;
    sin_half[lane] = cone.sin_half;
  }
  /// The union of each lane's pair (NormalCone::Union is this with one lane); unused lanes are
  /// open cones.
  static ConeLanes Union(const ConeLanes& a, const ConeLanes& b);
};

}  // namespace flagsim::sim
