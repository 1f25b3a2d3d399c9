// flagsim's flag built as Bullet 3.24's soft body (btSoftBody) with its public API, alone in a
// soft-rigid world: the same nodes, masses, pinned hoist edge, gravity, air friction and mean
// wind, and one link per flagsim spring. bullet_bench times it and scores it against the lab's
// reference.
//
//   links      flagsim's six spring families, one material each: structural (0,1) (1,0), shear
//              (1,1) (1,-1), bend (0,2) (2,0). Appended by hand rather than by CreatePatch (one
//              diagonal per cell) and generateBendingConstraints(2) (on a grid it also links the
//              diagonals, or knight's moves once diagonals exist, and builds an n^2 adjacency
//              matrix: 600 MB at 128 x 96).
//   stiffness  kLST from each family's spring constant k, see LinkStiffness: not an exact match.
//              Bullet's links have no damping: flagsim's spring damping is left out.
//   air        kDP = 1 - exp(-friction h), flagsim's air friction over one step.
//   wind       the mean wind only (Bullet's wind is one velocity per body: no gusts), through
//              aeromodel F_TwoSided: per face rho kLF 2A0 (n.u) |u|^2 n, A0 its rest area,
//              u = w - v, a third to each node (a share that would change a node's velocity by
//              more than its speed in one step is cut to one that stops it along the share).
//              kLF = C / (2 rho |w|^2) makes it flagsim's C A (n.w) n when |u| = |w| and A = A0;
//              kDG = 0, as flagsim's law has no drag along the wind.
//   solver     m_cfg.piterations position iterations; stepSimulation(h, 0): exactly one internal
//              step of h. Single precision (Bullet's build).
#pragma once

#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

#include "server/sim/cloth_model.hpp"
#include "server/sim/cloth_state.hpp"
#include "server/sim/sim_params.hpp"
#include "server/sim/wind_field.hpp"

namespace flagsim {

/// Bullet's kLST for a spring of constant k (N/m) whose nodes' inverse masses sum to w (1/kg), at
/// step h (s) with n position iterations. An XPBD projection of the spring as a constraint of
/// compliance 1/k closes the fraction f = k h^2 w / (1 + k h^2 w) of its error in one step (what
/// backward Euler does to the spring alone); Bullet closes kLST of it per iteration, so n
/// iterations on a lone link close 1 - (1 - kLST)^n. Hence kLST = 1 - (1 - f)^(1/n). Coupled
/// links converge more slowly under Gauss-Seidel, so the sheet comes out softer than flagsim's.
double LinkStiffness(double k, double w, double h, int n);

/// The flag of `params` (grid, masses, springs, gravity, friction, wind coefficient) in the mean
/// of `wind`, as a Bullet soft body stepped by h with `iterations` position iterations.
class BulletFlag {
 public:
  BulletFlag(const sim::SimParams& params, const sim::WindSettings& wind, double h, int iterations);
  ~BulletFlag();
  BulletFlag(const BulletFlag&) = delete;
  BulletFlag& operator=(const BulletFlag&) = delete;

  /// One internal step of exactly h (maxSubSteps = 0: no fixed-step accumulator).
  void Step() { world_.stepSimulation(btScalar(h_), 0); }

  /// Every position and velocity finite and no velocity component above `runaway` m/s.
  bool IsSound(double runaway) const;

  /// Bullet's nodes as flagsim's state: node i is flagsim's node i (row-major, ClothModel::index).
  sim::ClothState<double> State() const;

  /// kLST per spring family, in ClothModel::families order.
  const std::vector<double>& link_stiffness() const { return link_stiffness_; }

 private:
  void AddBody(const sim::ClothModel<double>& model);
  void AddLinks(const sim::ClothModel<double>& model, int iterations);
  void AddFaces(const sim::ClothModel<double>& model);
  void Configure(const sim::SimParams& params, const sim::WindSettings& wind, int iterations);

  double h_;  ///< s per step
  btSoftBodyRigidBodyCollisionConfiguration collision_configuration_;
  btCollisionDispatcher dispatcher_{&collision_configuration_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btSoftRigidDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &collision_configuration_};
  std::unique_ptr<btSoftBody> body_;
  std::vector<double> link_stiffness_;
};

}  // namespace flagsim
