#include "client/gateway/scene_update.hpp"

#include <nlohmann/json.hpp>

#include "client/gateway/bus_json.hpp"

namespace flagsim::gateway {
namespace {

using nlohmann::json;

json ZUp(double x, double y, double z) { return {{"x", x}, {"y", -z}, {"z", y}}; }

json Color(double r, double g, double b) { return {{"r", r}, {"g", g}, {"b", b}, {"a", 1.0}}; }

json IdentityPose(const json& position) {
  return {{"position", position}, {"orientation", {{"x", 0}, {"y", 0}, {"z", 0}, {"w", 1}}}};
}

json Entity(const state_t& state, const char* id) {
  json entity = {{"timestamp", TimeJson(state.utime)},
                 {"frame_id", "world"},
                 {"id", id},
                 {"lifetime", {{"sec", 0}, {"nsec", 0}}},
                 {"frame_locked", false}};
  for (const char* list :
       {"metadata", "arrows", "cubes", "spheres", "cylinders", "lines", "triangles", "texts", "models"}) {
    entity[list] = json::array();
  }
  return entity;
}

// Cell (r, c) with corners a = r cols + c, b = a + 1, d = a + cols, e = d + 1: triangles
// (a, d, b) and (b, d, e), the winding the renderer's mesh uses.
json ClothTriangles(const state_t& state) {
  json points = json::array(), indices = json::array();
  for (size_t i = 0; i + 2 < state.position.size(); i += 3) {
    points.push_back(ZUp(state.position[i], state.position[i + 1], state.position[i + 2]));
  }
  for (int r = 0; r + 1 < state.rows; ++r) {
    for (int c = 0; c + 1 < state.cols; ++c) {
      const int a = r * state.cols + c, b = a + 1, d = a + state.cols, e = d + 1;
      for (int index : {a, d, b, b, d, e}) indices.push_back(index);
    }
  }
  return {{"pose", IdentityPose(ZUp(0, 0, 0))},
          {"points", points},
          {"color", Color(0.78, 0.16, 0.16)},
          {"colors", json::array()},
          {"indices", indices}};
}

// A cylinder's pose is its centre; its size the diameters and the height (along z).
json PoleCylinder(const state_t& state) {
  const double height = state.pole_top[1];
  return {{"pose", IdentityPose(ZUp(state.pole_top[0], height / 2, state.pole_top[2]))},
          {"size", {{"x", 2 * state.pole_radius}, {"y", 2 * state.pole_radius}, {"z", height}}},
          {"bottom_scale", 1.0},
          {"top_scale", 1.0},
          {"color", Color(0.75, 0.75, 0.78)}};
}

}  // namespace

std::string SceneUpdateJson(const state_t& state) {
  if (state.cols < 2 || state.rows < 2 || state.position.size() != size_t(3) * state.cols * state.rows)
    return "";
  json flag = Entity(state, "flag");
  flag["triangles"].push_back(ClothTriangles(state));
  json pole = Entity(state, "pole");
  pole["cylinders"].push_back(PoleCylinder(state));
  return json{{"deletions", json::array()}, {"entities", {flag, pole}}}.dump();
}

}  // namespace flagsim::gateway
