#include "server/service/geomorph.hpp"

#include <algorithm>

#include "server/sim/resample.hpp"

namespace flagsim {

Geomorph::Geomorph(const sim::ClothModel<float>& fine, const sim::ClothState<float>& fine_state,
                   const sim::ClothModel<float>& coarse, const sim::ClothState<float>& coarse_state)
    : fine_(fine), coarse_cols_(coarse.cols), coarse_rows_(coarse.rows), start_(coarse_state.time) {
  // D = fine(t0) - R(coarse(t0))
  const sim::ClothState<float> surface = sim::Resample(coarse, coarse_state, fine_);
  detail_.Resize(fine_.num_nodes());
  for (int i = 0; i < fine_.num_nodes(); ++i) {
    detail_.x[i] = fine_state.x[i] - surface.x[i];
    detail_.y[i] = fine_state.y[i] - surface.y[i];
    detail_.z[i] = fine_state.z[i] - surface.z[i];
  }
}

bool Geomorph::Blends(const sim::ClothModel<float>& coarse, double time) const {
  return coarse.cols == coarse_cols_ && coarse.rows == coarse_rows_ && time >= start_ && time < start_ + kSeconds;
}

// R(coarse(t)) + w(t) D, w falling smoothly from 1 to 0
void Geomorph::Draw(const sim::ClothModel<float>& coarse, const sim::ClothState<float>& coarse_state,
                    std::vector<float>* x, std::vector<float>* y, std::vector<float>* z) const {
  const double s = std::clamp((coarse_state.time - start_) / kSeconds, 0.0, 1.0);
  const float w = float(1 - s * s * (3 - 2 * s));
  const sim::ClothState<float> surface = sim::Resample(coarse, coarse_state, fine_);
  const int n = fine_.num_nodes();
  x->resize(n);
  y->resize(n);
  z->resize(n);
  for (int i = 0; i < n; ++i) {
    (*x)[i] = surface.x[i] + w * detail_.x[i];
    (*y)[i] = surface.y[i] + w * detail_.y[i];
    (*z)[i] = surface.z[i] + w * detail_.z[i];
  }
}

}  // namespace flagsim
