// How the culling packs its numbers into vector lanes, and what the float lanes give up to
// rounding. The build targets AVX2 (x86-64-v3, CMakeLists.txt): 256-bit registers, four doubles
// or eight floats, and 128-bit ones, four floats.
//
//   cones of regions   ConeLanes: kConeLanes cones side by side, each quantity contiguous (axis
//                      x, y, z, cos and sin of the half-angle), so that the unions of kConeLanes
//                      pairs of halves are joined in one pass of vector instructions
//                      (ConeLanes::Union, normal_cone.cpp), a level of the patch tree at a time.
//   cones of patches   PatchLanes: kPatchLanes patches of a patch row in the lanes of a float
//                      vector. Each triangle's normals wait in slots (SlotRows): the same slot of
//                      consecutive patches of a row is contiguous, so one load gives it for all
//                      the lanes (CollisionCulling::PatchCones).
//   swept boxes        LaneBox: lo and hi in kBoxLanes floats, x, y, z and a spare lane held at
//                      0, so that an overlap test is a few vector instructions.
//
// Float halves the memory of boxes and normals; what it loses is covered by margins that make
// every float bound conservative: a bound is moved outwards by kRoundingShare of itself and
// kRoundingLeast before it is rounded (FloatBelow and FloatAbove, collision_culling.cpp), and the
// patches' cones are widened by kConeRounding.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

#include "server/sim/collision/normal_cone.hpp"

namespace flagsim::sim {

/// Doubles in a 256-bit register: regions whose cones ConeLanes::Union joins at once.
inline constexpr int kConeLanes = 4;
/// Floats in a 256-bit register: patches whose leaf cones PatchCones works out at once.
inline constexpr int kPatchLanes = 8;
/// Floats in a 128-bit register: a box's x, y and z, and the spare lane.
inline constexpr int kBoxLanes = 4;
inline constexpr int kBoxSpareLane = 3;  ///< 0 in lo and hi: never decides an overlap

// ---- rounding into float ---------------------------------------------------------------------

/// Rounding to nearest puts float(y) within |y| 2^-24 of y (and within 2^-150 below 2^-126), so
/// lowering a bound by kRoundingShare of itself and kRoundingLeast more before rounding keeps it
/// below; raising it likewise keeps it above. Under a micrometre at the flag's few metres.
inline constexpr double kRoundingShare = 0x1p-22, kRoundingLeast = 1e-30;
/// What a patch's cone takes off its cosine for its float arithmetic: the rounding of the
/// normals, the dot products, the square roots and quotients, and of the axis to a unit vector
/// come to some 2^-21 at most (CollisionCulling::PatchCones). On the angle that is at least
/// 2^-16 rad, more than the unions above the patches lose (normal_cone.hpp).
inline constexpr double kConeRounding = 0x1p-16;

// ---- the packings ----------------------------------------------------------------------------

/// kConeLanes cones side by side (see above). Unused lanes are open cones.
struct ConeLanes {
  static constexpr int kLanes = kConeLanes;
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
  /// The union of each lane's pair: NormalCone::UnionByAngles in cosines and sines, every lane
  /// at once (normal_cone.cpp); unused lanes are open cones.
  static ConeLanes Union(const ConeLanes& a, const ConeLanes& b);
};

/// One float per patch of a block of kPatchLanes patches.
using PatchLanes = Eigen::Array<float, kPatchLanes, 1>;

/// Patch columns rounded up to whole blocks of kPatchLanes: the stride of a slot's row.
inline int LaneColumns(int patch_cols) { return (patch_cols + kPatchLanes - 1) / kPatchLanes * kPatchLanes; }

/// Where the triangle normals of the patches wait: a patch's triangles fill its slots 0 to
/// `slots` - 1, and slot s of the patch in row pr and column pc is row (pr slots + s) lane_cols
/// + pc of the arrays that hold them. Lane-padding columns and slots whose triangle lies past the
/// flag's edge (a patch cut short) stay zero.
struct SlotRows {
  int slots = 0;      ///< triangles a patch has at most
  int lane_cols = 0;  ///< LaneColumns of the patch columns

  int Row(int pr, int slot, int pc) const { return (pr * slots + slot) * lane_cols + pc; }
  int Count(int patch_rows) const { return patch_rows * slots * lane_cols; }
};

/// An axis-aligned box in float, rounded outwards from the double extent it bounds (see above),
/// at half the memory: it holds that extent, so a test in float finds every pair
/// the double one would, and the few it adds are farther apart than h, which the exact tests
/// reject.
struct LaneBox {
  using Lanes = Eigen::Array<float, kBoxLanes, 1>;
  static_assert(kBoxLanes == 4 && kBoxSpareLane == 3, "x, y, z and the spare lane");
  Lanes lo, hi;

  static LaneBox Empty() { return {Lanes::Constant(INFINITY), Lanes::Constant(-INFINITY)}; }
  /// The box from lo to hi, the spare lane 0 in both.
  static LaneBox Of(float lo_x, float lo_y, float lo_z, float hi_x, float hi_y, float hi_z) {
    return {{lo_x, lo_y, lo_z, 0.0f}, {hi_x, hi_y, hi_z, 0.0f}};
  }
  LaneBox Joined(const LaneBox& other) const { return {lo.min(other.lo), hi.max(other.hi)}; }
  /// Each lane of one box reaches the other's: other.hi - lo >= 0 and hi - other.lo >= 0.
  bool Overlaps(const LaneBox& other) const { return (other.hi - lo).min(hi - other.lo).minCoeff() >= 0; }
};

}  // namespace flagsim::sim
