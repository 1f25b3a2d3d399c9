// How a frame is shaded, from cheapest to the reference.
#pragma once

#include <string>
#include <vector>

namespace flagsim::render {

enum class ShadingMode {
  kWireframe,  ///< mesh edges only, Bresenham lines with a depth test
  kFlat,       ///< one lighting value per triangle
  kGouraud,    ///< lighting per vertex, interpolated (perspective-correct)
  kPhong,      ///< lighting per pixel from interpolated normals: the reference
};

/// Names as PARAM and scene files spell them, in ShadingMode order.
inline const std::vector<std::string>& ShadingModeNames() {
  static const std::vector<std::string> names = {"wireframe", "flat", "gouraud", "phong"};
  return names;
}

}  // namespace flagsim::render
