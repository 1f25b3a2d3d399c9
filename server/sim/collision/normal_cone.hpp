// A cone of directions: the unit vectors within a half-angle theta of a unit axis, carried as
// cos theta and sin theta. A surface whose normals all lie in a narrow cone (theta under 90
// degrees) over a whole step cannot meet itself then (Volino and Magnenat-Thalmann 1994, the
// normal-cone criterion): self-collision culls such regions of the cloth (self_collision.hpp).
#pragma once

#include "server/sim/collision/collision_geometry.hpp"

namespace flagsim::sim {

struct NormalCone {
  Point axis = Point::UnitZ();
  double cos_half = -1, sin_half = 0;  ///< the default: 180 degrees, any direction

  bool Narrow() const { return cos_half > 0; }

  /// The smallest cone holding both (normal_cone.cpp: one lane of ConeLanes::Union,
  /// lane_layout.hpp); any direction when that is not narrow.
  static NormalCone Union(const NormalCone& a, const NormalCone& b);
  /// Union(a, b).Narrow(), without the union's axis.
  static bool NarrowTogether(const NormalCone& a, const NormalCone& b) {
    return a.Narrow() && b.Narrow() && NarrowCones(a, b);
  }

 private:
  /// NarrowTogether of two narrow cones.
  static bool NarrowCones(const NormalCone& a, const NormalCone& b);
};

}  // namespace flagsim::sim
