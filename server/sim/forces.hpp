// Forces on every node of the flag: (x, v, t) => f.
//   gravity      m_i g
//   springs      k (|d| - L) d^ + c ((v_b - v_a) . d^) d^ on node a, d = x_b - x_a; k the
//                spring's stiffness, or its compression stiffness when |d| < L
//   bending      -B Q (x + beta v): the sheet's curvature (bending.hpp)
//   air friction -friction m_i v_i
//   wind         C A_j n_j (n_j . w) on face j, a third to each of its nodes; w - v_face with
//                relative wind
// Every node gathers its own springs and faces in a fixed order, so the result is the same bit
// for bit whatever the number of threads.
#pragma once

#include <algorithm>
#include <functional>
#include <vector>

#include "server/sim/cloth_model.hpp"
#include "server/sim/cloth_state.hpp"
#include "server/sim/sim_params.hpp"
#include "server/sim/wind_field.hpp"

namespace flagsim::sim {

/// Total force per node, N.
template <typename Real>
struct NodeForces {
  std::vector<Real> x, y, z;
};

/// Grid rows [begin, end): one share of an evaluation.
struct RowBand {
  int begin = 0, end = 0;
};

/// Band `band` of `bands`: contiguous rows, as even as can be.
inline RowBand BandOf(int rows, int band, int bands) {
  return {rows * band / bands, rows * (band + 1) / bands};
}

/// Bands to share `rows` among `threads`: one alone; else a few per thread, so a thread that loses
/// its core holds back a small share, while each band's runs stay long for the vector unit.
inline int BandCount(int rows, int threads) { return threads <= 1 ? 1 : std::min(rows, 4 * threads); }

/// m: the shortest spring length divided by. A shorter spring has no direction: its force,
/// Jacobian block and projection target are taken as zero, and 1 / kShortestSpring^2 stays
/// finite in float.
inline constexpr float kShortestSpring = 1e-9f;

/// Which forces an evaluation sums, as flags that combine (after MuJoCo's disable flags, but set
/// for the terms kept): an integrator that solves the springs as constraints leaves them out, one
/// that takes friction implicitly leaves that out too. The model and parameters stay as they are.
enum class ForceTerms : unsigned {
  kGravity = 1u << 0,   ///< m_i g
  kSprings = 1u << 1,   ///< every spring's stretch and damping
  kFriction = 1u << 2,  ///< air friction -friction m_i v_i
  kWind = 1u << 3,      ///< the faces' wind
  kBending = 1u << 4,   ///< the sheet's bending and its damping
  kAll = kGravity | kSprings | kFriction | kWind | kBending,
};
constexpr ForceTerms operator|(ForceTerms a, ForceTerms b) {
  return static_cast<ForceTerms>(static_cast<unsigned>(a) | static_cast<unsigned>(b));
}
/// `terms` less those of `dropped`.
constexpr ForceTerms Without(ForceTerms terms, ForceTerms dropped) {
  return static_cast<ForceTerms>(static_cast<unsigned>(terms) & ~static_cast<unsigned>(dropped));
}
/// Whether `terms` holds every term of `term`.
constexpr bool Includes(ForceTerms terms, ForceTerms term) {
  return (static_cast<unsigned>(terms) & static_cast<unsigned>(term)) == static_cast<unsigned>(term);
}

template <typename Real>
class ForceEvaluator {
 public:
  /// (state.x, state.v, t) => forces. Pinned nodes get forces too; integrators ignore them.
  /// `after_row(r)`, if given, runs on each row r once the thread that summed its forces has
  /// summed its whole band of rows, while they are still in cache: an update of row r's own
  /// nodes may go there (nothing reads positions or velocities once the springs and faces are
  /// done).
  void Evaluate(const ClothModel<Real>& model, const SimParams& params, const WindField& wind,
                const ClothState<Real>& state, double t, NodeForces<Real>* forces,
                ForceTerms terms = ForceTerms::kAll, const std::function<void(int)>& after_row = {});

 private:
  bool LaidOutFor(const ClothModel<Real>& model) const;  ///< whether the scratch fits the model
  void Resize(const ClothModel<Real>& model);
  void SampleWind(const ClothModel<Real>& model, const WindField& wind, double t);
  void SpringBand(const ClothModel<Real>& model, const ClothState<Real>& state, RowBand band);
  void WindBand(const ClothModel<Real>& model, const SimParams& params, const ClothState<Real>& state,
                RowBand band);
  void CurvatureBand(const ClothModel<Real>& model, const ClothState<Real>& state, RowBand band);
  void BendingBand(const ClothModel<Real>& model, RowBand band);
  void GatherBand(const ClothModel<Real>& model, const SimParams& params, const ClothState<Real>& state,
                  RowBand band, ForceTerms terms, NodeForces<Real>* forces) const;

  // Scratch, laid out on the node grid (forces.cpp says how).
  std::vector<int> layout_;               ///< cols, rows, then (dr, dc) per family, of the scratch
  std::vector<NodeForces<Real>> spring_;  ///< per family, at the spring's first node: the
                                          ///< force on that node (the far node gets minus it)
  NodeForces<Real> upper_, lower_;        ///< per cell: a third of each triangle's wind force
  NodeForces<Real> curvature_;            ///< 1/m per node, L (x + beta v) (bending.hpp's padding)
  NodeForces<Real> bending_;              ///< N per node: the bending force
  std::vector<Real> zero_;                ///< zeros, for families a model lacks
  std::vector<double> column_s_;          ///< m, each cell column's middle down the flag
  std::vector<Vec3> column_wind_;         ///< m/s, the wind there
  std::vector<Real> column_wind_x_, column_wind_y_, column_wind_z_;  ///< m/s, wind per cell column
  std::vector<Real> wind_x_, wind_y_, wind_z_;                       ///< m/s, wind per cell, on the node grid
};

/// Air friction as the force law applies it: the seed's scheme replaces it by -mu F.
inline double AirFriction(const SimParams& params) {
  return params.integrator == IntegratorKind::kSeed ? 0.0 : params.forces.friction;
}

}  // namespace flagsim::sim
