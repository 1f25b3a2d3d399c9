// The flat sheet's imperfection: a small, smooth, seeded displacement of the rest state out of
// its plane. A perfectly flat sheet with every force in its plane has no out-of-plane force to
// start buckling, however soft it is in compression; real cloth is never that flat.
//
//   z(u, v) = A s(u, v) / max over the nodes |s|,
//   s(u, v) = sum over m = 1..3, n = 0..2 of a_mn / (m + n) sin((2m - 1) pi u / 2) cos(n pi v)
//
// with u = c / (cols - 1) along the flag from the hoist, v = r / (rows - 1) down it, A the
// `imperfection` parameter and a_mn uniform in [-1, 1] from a generator with a fixed seed. The
// sines are a cantilever's shapes (zero at the hoist, flat at the fly), the cosines those of free
// top and bottom edges; the weights 1 / (m + n) favour the smoothest. Only free nodes move, only
// in z; rest lengths stay the flat grid's, so the flag starts unstrained to first order in A.
// The result depends on the parameters alone: the same bits on every replay and thread count.
#pragma once

#include "server/sim/cloth_model.hpp"
#include "server/sim/sim_params.hpp"

namespace flagsim::sim {

/// (params.imperfection, grid) => model->rest_z of the free nodes += z(u, v) above; nothing
/// when the imperfection is 0.
template <typename Real>
void AddRestImperfection(const SimParams& params, ClothModel<Real>* model);

}  // namespace flagsim::sim
