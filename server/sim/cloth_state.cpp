#include "server/sim/cloth_state.hpp"

#include <xxhash.h>

namespace flagsim::sim {

template <typename Real>
uint64_t StateHash(const ClothState<Real>& state) {
  XXH3_state_t* hasher = XXH3_createState();
  XXH3_64bits_reset(hasher);
  for (const std::vector<Real>* array : {&state.x, &state.y, &state.z, &state.vx, &state.vy, &state.vz}) {
    XXH3_64bits_update(hasher, array->data(), array->size() * sizeof(Real));
  }
  const uint64_t hash = XXH3_64bits_digest(hasher);
  XXH3_freeState(hasher);
  return hash;
}

template <typename Real>
double KineticEnergy(const ClothModel<Real>& model, const ClothState<Real>& state) {
  double energy = 0;
  for (int i = 0; i < state.num_nodes(); ++i) {
    if (model.pinned(i)) continue;
    const double vx = state.vx[i], vy = state.vy[i], vz = state.vz[i];
    energy += 0.5 * double(model.mass[i]) * (vx * vx + vy * vy + vz * vz);
  }
  return energy;
}

template uint64_t StateHash<float>(const ClothState<float>&);
template uint64_t StateHash<double>(const ClothState<double>&);
template double KineticEnergy<float>(const ClothModel<float>&, const ClothState<float>&);
template double KineticEnergy<double>(const ClothModel<double>&, const ClothState<double>&);

}  // namespace flagsim::sim
