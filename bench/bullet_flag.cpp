#include "bench/bullet_flag.hpp"

#include <cmath>

namespace flagsim {
namespace {

constexpr double kAirDensity = 1.2;  ///< kg/m^3, Bullet's rho

}  // namespace

double LinkStiffness(double k, double w, double h, int n) {
  const double stiffness = k * h * h * w;
  const double fraction = stiffness / (1 + stiffness);
  return 1 - std::pow(1 - fraction, 1.0 / n);
}

BulletFlag::BulletFlag(const sim::SimParams& params, const sim::WindSettings& wind, double h, int iterations)
    : h_(h) {
  const sim::ClothModel<double> model = sim::BuildClothModel<double>(params);
  AddBody(model);
  AddLinks(model, iterations);
  AddFaces(model);
  Configure(params, wind, iterations);
  world_.addSoftBody(body_.get());
}

BulletFlag::~BulletFlag() { world_.removeSoftBody(body_.get()); }

bool BulletFlag::IsSound(double runaway) const {
  for (int i = 0; i < body_->m_nodes.size(); ++i) {
    const btSoftBody::Node& node = body_->m_nodes[i];
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(node.m_x[k]) || !(std::abs(node.m_v[k]) <= runaway)) return false;
    }
  }
  return true;
}

sim::ClothState<double> BulletFlag::State() const {
  sim::ClothState<double> state;
  for (int i = 0; i < body_->m_nodes.size(); ++i) {
    const btSoftBody::Node& node = body_->m_nodes[i];
    state.x.push_back(node.m_x.x());
    state.y.push_back(node.m_x.y());
    state.z.push_back(node.m_x.z());
    state.vx.push_back(node.m_v.x());
    state.vy.push_back(node.m_v.y());
    state.vz.push_back(node.m_v.z());
  }
  return state;
}

// Node (r, c) at flagsim's rest position, with flagsim's mass; 0 (pinned) on the hoist column.
void BulletFlag::AddBody(const sim::ClothModel<double>& model) {
  const int n = model.num_nodes();
  std::vector<btVector3> positions(n);
  std::vector<btScalar> masses(n);
  for (int i = 0; i < n; ++i) {
    positions[i] = btVector3(btScalar(model.rest_x[i]), btScalar(model.rest_y[i]), btScalar(model.rest_z[i]));
    masses[i] = model.pinned(i) ? btScalar(0) : btScalar(model.mass[i]);
  }
  body_ = std::make_unique<btSoftBody>(&world_.getWorldInfo(), n, positions.data(), masses.data());
}

// Each family a material, its kLST mapped from the spring constant with w = 2 / m of an
// interior node; one link per flagsim spring (r, c) -> (r + dr, c + dc).
void BulletFlag::AddLinks(const sim::ClothModel<double>& model, int iterations) {
  const double w = 2 * model.inverse_mass[model.index(1, 1)];
  for (const sim::SpringFamily<double>& family : model.families) {
    btSoftBody::Material* material = body_->appendMaterial();
    material->m_kLST = btScalar(LinkStiffness(family.stiffness, w, h_, iterations));
    link_stiffness_.push_back(material->m_kLST);
    for (int r = 0; r + family.dr < model.rows; ++r) {
      for (int c = family.first_col(); c < family.end_col(model.cols); ++c) {
        body_->appendLink(model.index(r, c), model.index(r + family.dr, c + family.dc), material);
      }
    }
  }
}

// flagsim's two triangles per cell, in its winding: upper (r, c) (r+1, c) (r, c+1), lower
// (r+1, c) (r+1, c+1) (r, c+1).
void BulletFlag::AddFaces(const sim::ClothModel<double>& model) {
  for (int r = 0; r + 1 < model.rows; ++r) {
    for (int c = 0; c + 1 < model.cols; ++c) {
      body_->appendFace(model.index(r, c), model.index(r + 1, c), model.index(r, c + 1));
      body_->appendFace(model.index(r + 1, c), model.index(r + 1, c + 1), model.index(r, c + 1));
    }
  }
}

// Gravity, air friction, wind and solver as the header describes.
void BulletFlag::Configure(const sim::SimParams& params, const sim::WindSettings& wind, int iterations) {
  const btVector3 gravity(0, btScalar(-params.forces.gravity), 0);
  world_.setGravity(gravity);
  world_.getWorldInfo().m_gravity = gravity;
  world_.getWorldInfo().air_density = btScalar(kAirDensity);
  const sim::Vec3& w = wind.velocity;
  const double speed_squared = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  btSoftBody::Config& config = body_->m_cfg;
  config.piterations = iterations;
  config.kDP = btScalar(1 - std::exp(-params.forces.friction * h_));
  config.aeromodel = btSoftBody::eAeroModel::F_TwoSided;
  config.kLF = btScalar(params.forces.wind_coefficient / (2 * kAirDensity * speed_squared));
  config.kDG = 0;
  body_->setWindVelocity(btVector3(btScalar(w[0]), btScalar(w[1]), btScalar(w[2])));
}

}  // namespace flagsim
