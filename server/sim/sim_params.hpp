// Everything that defines the flag's physics and its numerics, with every default in place.
// Scene files and the PARAM channel override fields; see server/scene/parameter_table.cpp for
// the allowed ranges.
#pragma once

#include <cstring>

namespace flagsim::sim {

enum class IntegratorKind {
  kSymplecticEuler,     ///< v += h a(x, v); x += h v. Order 1, stable for h < 2 / w_max.
  kSeed,                ///< the seed's scheme: symplectic Euler with friction -mu F (mu a fraction)
  kExplicitEuler,       ///< x += h v; v += h a(x, v). Order 1, stable only with enough damping.
  kVelocityVerlet,      ///< kick, drift, kick. Order 2, stable for h < 2 / w_max.
  kRk4,                 ///< classic Runge-Kutta. Order 4, four force evaluations, h < 2.6 / w_max.
  kXpbd,                ///< springs as compliant constraints, Gauss-Seidel. Unconditionally stable.
  kImplicitEuler,       ///< linearised backward Euler by conjugate gradient. Unconditionally stable.
  kProjectiveDynamics,  ///< Liu et al. 2013 local/global, one factorisation. Unconditionally stable.
};

/// The coefficients of the forces: what may change while the flag flies, in place, without
/// rebuilding it. Simulation::SetControls copies them whole, and the parameter table makes a
/// parameter animatable (keyframes may move it) exactly when it lives here.
struct ForceCoefficients {
  // The sheet's moduli. Each spring's constant is modulus * dx * dy / L^2 (L its rest length),
  // and the bending acts on the sheet's curvature, so the flag's response does not change when the
  // grid is refined (cloth_model.hpp, bending.hpp).
  double stiffness = 2000.0;           ///< N/m, structural springs (neighbours along rows, columns)
  double shear_stiffness = 200.0;      ///< N/m, diagonal springs
  double bending_stiffness = 5e-3;     ///< N m, the sheet's resistance to bending (flexural rigidity)
  double damping = 0.05;               ///< N s/m, along every spring, scaled like the stiffness;
                                       ///< bending is damped in the same ratio to its stiffness

  // Air and gravity.
  double friction = 0.2;          ///< 1/s, air friction -friction m_i v_i (seed: fraction of F)
  double wind_coefficient = 1.0;  ///< N s/m^3: face force C A n (n . w)
  double gravity = 9.81;          ///< m/s^2, downward (-y)
};

/// Whether any coefficient differs, bit for bit (the struct holds doubles only, so no padding).
inline bool operator!=(const ForceCoefficients& a, const ForceCoefficients& b) {
  return std::memcmp(&a, &b, sizeof(ForceCoefficients)) != 0;
}

struct SimParams {
  // The flag: a grid of cols x rows nodes over width x height metres, hoist edge on the pole.
  int cols = 32;             ///< nodes along the flag (>= 2)
  int rows = 24;             ///< nodes down the flag (>= 2)
  double width = 1.5;        ///< m, along the flag (fly length)
  double height = 1.0;       ///< m, down the flag (hoist length)
  double mass = 0.25;        ///< kg, the whole flag
  double pole_height = 3.0;  ///< m, the pole's top; the flag's top edge hangs just below it

  ForceCoefficients forces;  ///< the sheet's moduli, the air's friction and the wind's pressure, gravity

  // Cloth against compression, itself, the pole and the ground.
  double compression = 0.3;    ///< compressive stiffness of structural and shear springs, as a fraction
                               ///< of their stiffness: cloth buckles rather than compress in its plane
  double imperfection = 1e-3;  ///< m, out of the plane: the rest state's largest departure from a
                               ///< flat sheet (smooth, seeded), which buckling grows from
  double pole_radius = 0.03;   ///< m: the pole is a cylinder the cloth cannot enter; the hoist edge is on it
  double pole_friction = 0.3;  ///< Coulomb friction coefficient of the cloth on the pole and the ground
  double thickness = 0.004;    ///< m: the least distance the cloth keeps from itself, the pole and the ground
  bool self_collision = true;  ///< the cloth does not pass through itself

  bool relative_wind = false;  ///< use w - v_face instead of w: damps flutter physically

  // Numerics.
  double dt = 0.002;  ///< s per step; commands apply between steps. An explicit
                      ///< integrator splits a step into substeps when stability asks.
  IntegratorKind integrator = IntegratorKind::kSymplecticEuler;
  int substeps = 0;                ///< per step; 0: chosen from the integrator's stability limit
  int solver_iterations = 10;      ///< XPBD and local/global iterations per step
  double solver_tolerance = 1e-3;  ///< implicit Euler: CG stops at this relative residual
  int threads = 1;                 ///< worker threads for forces and integration
  /// Nodes a thread must have for a step to be shared among threads: a loop handed to a second
  /// thread costs a few microseconds (about 3 on the 2-core machine of docs/benchmarks.md), which
  /// a smaller share does not earn back, so a smaller flag steps on one thread whatever `threads`
  /// says. Results are the same either way; tests lower it to run small flags on many threads.
  int min_nodes_per_thread = 4096;
};

}  // namespace flagsim::sim
