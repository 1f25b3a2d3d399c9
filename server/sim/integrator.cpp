#include "server/sim/integrator.hpp"

namespace flagsim::sim {

template <typename Real>
std::unique_ptr<Integrator<Real>> MakeIntegrator(IntegratorKind kind) {
  switch (kind) {
    case IntegratorKind::kSymplecticEuler:
      return MakeSymplecticEuler<Real>(false);
    case IntegratorKind::kSeed:
      return MakeSymplecticEuler<Real>(true);
    case IntegratorKind::kExplicitEuler:
      return MakeExplicitEuler<Real>();
    case IntegratorKind::kVelocityVerlet:
      return MakeVelocityVerlet<Real>();
    case IntegratorKind::kRk4:
      return MakeRk4<Real>();
    case IntegratorKind::kXpbd:
      return MakeXpbd<Real>();
    case IntegratorKind::kImplicitEuler:
      return MakeImplicitEuler<Real>();
    case IntegratorKind::kProjectiveDynamics:
      return MakeProjectiveDynamics<Real>();
  }
  return nullptr;
}
template std::unique_ptr<Integrator<float>> MakeIntegrator<float>(IntegratorKind);
template std::unique_ptr<Integrator<double>> MakeIntegrator<double>(IntegratorKind);

const std::vector<std::string>& IntegratorNames() {
  static const std::vector<std::string> names = {
      "symplectic_euler", "seed", "explicit_euler", "verlet", "rk4", "xpbd", "implicit_euler", "projective"};
  return names;
}

std::string IntegratorName(IntegratorKind kind) { return IntegratorNames()[static_cast<int>(kind)]; }

}  // namespace flagsim::sim
