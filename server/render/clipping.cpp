#include "server/render/clipping.hpp"

#include <algorithm>
#include <array>

namespace flagsim::render {
namespace {

/// The six planes as signed distances d(v) >= 0 inside.
constexpr int kPlanes = 6;
float Distance(int plane, const Eigen::Vector4f& v) {
  switch (plane) {
    case 0:
      return v.z() + v.w();  // near: z >= -w
    case 1:
      return v.w() - v.z();  // far: z <= w
    case 2:
      return kGuardBand * v.w() + v.x();  // left
    case 3:
      return kGuardBand * v.w() - v.x();  // right
    case 4:
      return kGuardBand * v.w() + v.y();  // bottom
    default:
      return kGuardBand * v.w() - v.y();  // top
  }
}

/// Outside the visible frustum (not the guard band) on `plane`'s side: for rejection.
bool OutsideView(int plane, const Eigen::Vector4f& v) {
  switch (plane) {
    case 0:
      return v.z() < -v.w();
    case 1:
      return v.z() > v.w();
    case 2:
      return v.x() < -v.w();
    case 3:
      return v.x() > v.w();
    case 4:
      return v.y() < -v.w();
    default:
      return v.y() > v.w();
  }
}

ClipVertex Lerp(const ClipVertex& inside, const ClipVertex& outside, float t) {
  ClipVertex v;
  v.clip = inside.clip + t * (outside.clip - inside.clip);
  for (int k = 0; k < kClipChannels; ++k) {
    v.channels[k] = inside.channels[k] + t * (outside.channels[k] - inside.channels[k]);
  }
  return v;
}

using Polygon = std::vector<ClipVertex>;

/// Keeps the part of `polygon` inside `plane`.
Polygon ClipAgainst(const Polygon& polygon, int plane) {
  Polygon kept;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const ClipVertex& current = polygon[i];
    const ClipVertex& next = polygon[(i + 1) % polygon.size()];
    const float dc = Distance(plane, current.clip), dn = Distance(plane, next.clip);
    if (dc >= 0) kept.push_back(current);
    if ((dc >= 0) != (dn >= 0)) {
      const ClipVertex& in = dc >= 0 ? current : next;
      const ClipVertex& out = dc >= 0 ? next : current;
      const float d_in = dc >= 0 ? dc : dn, d_out = dc >= 0 ? dn : dc;
      kept.push_back(Lerp(in, out, d_in / (d_in - d_out)));
    }
  }
  return kept;
}

}  // namespace

ClipTest ClassifyTriangle(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c) {
  bool crossing = false;
  for (int plane = 0; plane < kPlanes; ++plane) {
    if (OutsideView(plane, a.clip) && OutsideView(plane, b.clip) && OutsideView(plane, c.clip)) {
      return ClipTest::kOutside;
    }
    crossing |= Distance(plane, a.clip) < 0 || Distance(plane, b.clip) < 0 || Distance(plane, c.clip) < 0;
  }
  return crossing ? ClipTest::kCrossing : ClipTest::kInside;
}

void ClipTriangle(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c,
                  std::vector<ClipVertex>* out) {
  Polygon polygon = {a, b, c};
  for (int plane = 0; plane < kPlanes && polygon.size() >= 3; ++plane) polygon = ClipAgainst(polygon, plane);
  for (size_t i = 2; i < polygon.size(); ++i) {
    out->push_back(polygon[0]);
    out->push_back(polygon[i - 1]);
    out->push_back(polygon[i]);
  }
}

bool ClipLine(Eigen::Vector4f* a, Eigen::Vector4f* b) {
  float enter = 0, leave = 1;
  for (int plane = 0; plane < kPlanes; ++plane) {
    const float da = Distance(plane, *a), db = Distance(plane, *b);
    if (da < 0 && db < 0) return false;
    if (da < 0) enter = std::max(enter, da / (da - db));
    if (db < 0) leave = std::min(leave, da / (da - db));
  }
  if (enter > leave) return false;
  const Eigen::Vector4f start = *a, direction = *b - *a;
  *a = start + enter * direction;
  *b = start + leave * direction;
  return true;
}

}  // namespace flagsim::render
