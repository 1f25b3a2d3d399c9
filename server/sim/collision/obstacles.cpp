#include "server/sim/collision/obstacles.hpp"

#include <algorithm>
#include <cmath>

#include "server/sim/node_update.hpp"

namespace flagsim::sim {
namespace {

/// Removes the velocity into a surface of unit normal n (pointing out of it) and applies
/// Coulomb friction to what remains.
void Collide(double nx, double ny, double nz, double friction, double* vx, double* vy, double* vz) {
  const double normal = *vx * nx + *vy * ny + *vz * nz;
  if (normal >= 0) return;
  double tx = *vx - normal * nx, ty = *vy - normal * ny, tz = *vz - normal * nz;
  const double sliding = std::sqrt(tx * tx + ty * ty + tz * tz);
  const double kept = sliding > 0 ? std::max(0.0, 1 - friction * -normal / sliding) : 0.0;
  *vx = tx * kept;
  *vy = ty * kept;
  *vz = tz * kept;
}

}  // namespace

Obstacles Obstacles::Of(const SimParams& params) {
  return {params.pole_radius, params.pole_height, params.thickness / 2, params.pole_friction};
}

bool Obstacles::Inside(double x, double y, double z) const {
  return y < 0 || (y < pole_top && x * x + z * z < pole_radius * pole_radius);
}

namespace {

// The nodes of one row range.
template <typename Real>
void PushRangeOut(const ClothModel<Real>& model, const Obstacles& obstacles, NodeRange range,
                  ClothState<Real>* state) {
  const double radius = obstacles.pole_radius + obstacles.margin, ground = obstacles.margin;
  const double radius_squared = radius * radius;
  // Most substeps touch nothing: one branch-free pass finds whether any free node needs moving
  // (the pinned hoist edge lies on the pole's surface, within the margin).
  const Real *xs = state->x.data(), *ys = state->y.data(), *zs = state->z.data();
  const Real* inverse_mass = model.inverse_mass.data();
  const Real low = Real(ground), top = Real(obstacles.pole_top), inside = Real(radius_squared);
  int touching = 0;
#pragma omp simd reduction(| : touching)
  for (int i = range.begin; i < range.end; ++i) {
    const int in_pole = int(ys[i] < top) & int(xs[i] * xs[i] + zs[i] * zs[i] < inside);
    touching |= int(inverse_mass[i] != Real(0)) & (int(ys[i] < low) | in_pole);
  }
  if (touching == 0) return;
  for (int i = range.begin; i < range.end; ++i) {
    const double x = state->x[i], y = state->y[i], z = state->z[i];
    const double rho_squared = x * x + z * z;
    const bool below = y < ground;
    const bool in_pole = y < obstacles.pole_top && rho_squared < radius_squared;
    if (!(below || in_pole) || model.pinned(i)) continue;
    double vx = state->vx[i], vy = state->vy[i], vz = state->vz[i];
    double px = x, py = y, pz = z;
    if (in_pole) {  // out through the side, or up onto the top if that is nearer
      const double rho = std::sqrt(rho_squared);
      const double side = radius - rho, up = obstacles.pole_top + ground - y;
      if (up < side) {
        py = y + up;
        Collide(0, 1, 0, obstacles.friction, &vx, &vy, &vz);
      } else {
        const double nx = rho > 0 ? x / rho : 1.0, nz = rho > 0 ? z / rho : 0.0;
        px = nx * radius;
        pz = nz * radius;
        Collide(nx, 0, nz, obstacles.friction, &vx, &vy, &vz);
      }
    }
    if (py < ground) {
      py = ground;
      Collide(0, 1, 0, obstacles.friction, &vx, &vy, &vz);
    }
    state->x[i] = Real(px);
    state->y[i] = Real(py);
    state->z[i] = Real(pz);
    state->vx[i] = Real(vx);
    state->vy[i] = Real(vy);
    state->vz[i] = Real(vz);
  }
}

}  // namespace

// Row by row on the threads, each row on the thread that stepped it (node_update.hpp's
// ForEachRow shares rows as the integrators do): the nodes stay in that core's cache.
template <typename Real>
void PushOutOfObstacles(const ClothModel<Real>& model, const Obstacles& obstacles, int threads,
                        ClothState<Real>* state) {
  ForEachRow(model.rows, model.cols, threads,
             [&](NodeRange row) { PushRangeOut(model, obstacles, row, state); });
}

template void PushOutOfObstacles(const ClothModel<float>&, const Obstacles&, int, ClothState<float>*);
template void PushOutOfObstacles(const ClothModel<double>&, const Obstacles&, int, ClothState<double>*);

}  // namespace flagsim::sim
