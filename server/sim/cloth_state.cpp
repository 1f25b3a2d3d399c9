#include "cloth_state.hpp"

#include <cstring>

namespace flagsim::sim {
namespace {

constexpr uint64_t kFnvOffset = 0xcbf29ce484222325ull;
constexpr uint64_t kFnvPrime = 0x100000001b3ull;

template <typename Real>
uint64_t HashArray(const std::vector<Real>& values, uint64_t hash) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
  const size_t size = values.size() * sizeof(Real);
  for (size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * kFnvPrime;
  return hash;
}

}  // namespace

template <typename Real>
uint64_t StateHash(const ClothState<Real>& state) {
  uint64_t hash = kFnvOffset;
  for (const std::vector<Real>* array : {&state.x, &state.y, &state.z, &state.vx, &state.vy, &state.vz}) {
    hash = HashArray(*array, hash);
  }
  return hash;
}

template uint64_t StateHash<float>(const ClothState<float>&);
template uint64_t StateHash<double>(const ClothState<double>&);

}  // namespace flagsim::sim
