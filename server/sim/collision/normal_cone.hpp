// A cone of directions: the unit vectors within a half-angle theta of a unit axis, carried as
// cos theta and sin theta.
//
// The criterion (Volino and Magnenat-Thalmann 1994, "Efficient self-collision detection on
// smoothly discretized surface animations using geometrical shape regularity"): a connected
// surface cannot meet itself when some direction V has N . V > 0 for every normal N of it and
// the surface's contour, projected along V, does not cross itself. In the normal-cone form
// (Provot 1997): the normals lie in a cone of half-angle under 90 degrees ("narrow"), and V is
// its axis. The culling tests the cone alone and not the contour (README.md says what that
// leaves out); its cones hold every normal over the whole step, not at one moment.
//
// The cones of a tree of regions are joined upwards, two halves at a time: the union of two
// cones is the smallest cone holding both (UnionByAngles states it by its angles). The culling
// joins kConeLanes pairs at a time in cosines and sines (ConeLanes::Union, lane_layout.hpp),
// which is that union up to rounding: under 1e-7 rad on the half-angle and the axis, the error
// of an angle taken from its cosine when the axes are all but parallel (normal_cone_test.cpp
// measures 1e-8). It promises no margin of its own: the patches' cones carry one,
// kConeRounding, at least 1.5e-5 rad, nearly ten times what the 16 levels above the patches of
// the largest flag (512 x 512 nodes) could lose at 1e-7 each.
#pragma once

#include "server/sim/collision/collision_geometry.hpp"

namespace flagsim::sim {

struct NormalCone {
  Point axis = Point::UnitZ();
  double cos_half = -1, sin_half = 0;  ///< the default: 180 degrees, any direction

  /// Under 90 degrees: a region whose normals lie in it cannot meet itself.
  bool Narrow() const { return cos_half > 0; }

  /// The smallest cone holding both, by its angles, one cone at a time: the reference that
  /// ConeLanes::Union is tested against. Any direction when that is not narrow.
  static NormalCone UnionByAngles(const NormalCone& a, const NormalCone& b);
  /// The same union as the culling works it out: one lane of ConeLanes::Union.
  static NormalCone Union(const NormalCone& a, const NormalCone& b);
  /// Union(a, b).Narrow(), without the union's axis: two touching regions whose cones are
  /// narrow together cannot meet each other (their union is one connected surface).
  static bool NarrowTogether(const NormalCone& a, const NormalCone& b) {
    return a.Narrow() && b.Narrow() && NarrowCones(a, b);
  }

 private:
  /// NarrowTogether of two narrow cones.
  static bool NarrowCones(const NormalCone& a, const NormalCone& b);
};

}  // namespace flagsim::sim
