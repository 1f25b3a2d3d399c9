// Forces on every node of the flag: (x, v, t) => f.
//   gravity      m_i g
//   springs      k (|d| - L) d^ + c ((v_b - v_a) . d^) d^ on node a, d = x_b - x_a
//   air friction -friction m_i v_i
//   wind         C A_j n_j (n_j . w) on face j, a third to each of its nodes; w - v_face with
//                relative wind
// Every node gathers its own springs and faces in a fixed order, so the result is the same bit
// for bit whatever the number of threads.
#pragma once

#include <functional>
#include <vector>

#include "cloth_model.hpp"
#include "cloth_state.hpp"
#include "sim_params.hpp"
#include "wind_field.hpp"

namespace flagsim::sim {

/// Total force per node, N.
template <typename Real>
struct NodeForces {
  std::vector<Real> x, y, z;
};

/// Which forces to sum: all of them, or all but the springs (for integrators that solve the
/// springs themselves as constraints).
enum class ForceTerms { kAll, kExternal };

template <typename Real>
class ForceEvaluator {
 public:
  /// (state.x, state.v, t) => forces. Pinned nodes get forces too; integrators ignore them.
  /// `after_row(r)`, if given, runs as soon as row r's forces are summed, on the same thread,
  /// while they are still in cache: an update of row r's own nodes may go there (nothing reads
  /// a node's position or velocity once its row's springs and faces are done).
  void Evaluate(const ClothModel<Real>& model, const SimParams& params, const WindField& wind,
                const ClothState<Real>& state, double t, NodeForces<Real>* forces,
                ForceTerms terms = ForceTerms::kAll, const std::function<void(int)>& after_row = {});

 private:
  void Resize(const ClothModel<Real>& model);
  void SampleWind(const ClothModel<Real>& model, const WindField& wind, double t);
  void SpringRow(const ClothModel<Real>& model, const ClothState<Real>& state, int r);
  void WindRow(const ClothModel<Real>& model, const SimParams& params, const ClothState<Real>& state, int r);
  void GatherRow(const ClothModel<Real>& model, const SimParams& params, const ClothState<Real>& state, int r,
                 ForceTerms terms, NodeForces<Real>* forces) const;

  // Scratch, sized to the model.
  std::vector<NodeForces<Real>> spring_;        ///< per family, indexed by the spring's first node:
                                                ///< force on that node (the far node gets minus it)
  NodeForces<Real> upper_, lower_;              ///< per cell: a third of each triangle's wind force
  std::vector<Real> wind_x_, wind_y_, wind_z_;  ///< m/s, wind per cell column
};

/// Air friction as the force law applies it: the seed's scheme replaces it by -mu F.
inline double AirFriction(const SimParams& params) {
  return params.integrator == IntegratorKind::kSeed ? 0.0 : params.friction;
}

}  // namespace flagsim::sim
