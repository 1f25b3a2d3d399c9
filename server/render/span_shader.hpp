// How the tiles shade a triangle's pixels, shared by the single-sample spans (tile_raster.cpp)
// and the multisampled rows (multisample_raster.cpp): the triangle's planes side by side, and
// shaders that colour a block of kSpanLanes pixels of one row at once.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "server/render/ground_shadow.hpp"
#include "server/render/mesh.hpp"
#include "server/render/shading.hpp"
#include "server/render/srgb.hpp"
#include "server/render/texture_filter.hpp"
#include "server/render/tile_raster.hpp"
#include "server/render/triangle_setup.hpp"

namespace flagsim::render {

/// A triangle's planes side by side: depth, 1 / w, the channels, then zeros up to whole
/// vectors. A row's values of them all are then a few vector operations.
struct Planes {
  static constexpr int kDepth = 0, kInverseW = 1, kChannel = 2;
  static constexpr int kCount = 16;
  static_assert(kChannel + kPlaneChannels <= kCount);

  explicit Planes(const TriangleSetup& t) {
    const auto put = [this](int k, const Plane& plane) {
      origin[k] = plane.origin;
      dx[k] = plane.dx;
      dy[k] = plane.dy;
    };
    put(kDepth, t.depth);
    put(kInverseW, t.inverse_w);
    for (int k = 0; k < kPlaneChannels; ++k) put(kChannel + k, t.channels[k]);
  }

  /// Every plane along row fy: at[k] + dx[k] * fx at fx pixels from the box's first column.
  void AlongRow(float fy, float at[kCount]) const {
#pragma omp simd
    for (int k = 0; k < kCount; ++k) at[k] = origin[k] + dy[k] * fy;
  }

  alignas(32) float origin[kCount] = {};
  alignas(32) float dx[kCount] = {};
  alignas(32) float dy[kCount] = {};
};

/// What a material's surface adds to the interpolated light.
enum class Surface {
  kPlain,      ///< its colour
  kPatterned,  ///< its colour times the pattern, filtered at (u, v)
  kShadowed,   ///< its colour, in the ground's shadow at (u, v) = (x, z) (ground_shadow.hpp)
  kCutout,     ///< kPatterned by a pattern with transparent texels: its alpha too
};

/// Gouraud and flat: colour = base * D + S (linear light, encoded to sRGB bytes) with D, S the
/// interpolated light (channels 0-5) and base the material's colour, times the pattern filtered
/// at (u, v) (channels 6, 7) and the triangle's level of detail when kPatterned
/// (texture_filter.hpp); kShadowed takes the sun's share of D and S away in the shadow s at
/// (u, v): base * (D - s Dsun) + S (1 - s).
/// kCutout: as kPatterned with the pattern's straight colour, and its alpha for each pixel.
/// Perspective-correct: each channel is (channel / w) / (1 / w). Shades a block of kSpanLanes
/// pixels at once.
template <Surface kSurface>
class BlockShader {
 public:
  static constexpr int kChannels = kSurface == Surface::kPlain ? 6 : 8;
  static constexpr bool kPattern = kSurface == Surface::kPatterned || kSurface == Surface::kCutout;

  /// The context's pattern is read only when kPatterned or kCutout, at level of detail `lod`;
  /// its shadow only when kShadowed.
  BlockShader(const Planes& planes, const Material& material, const ShadeContext& context, float lod = 0)
      : planes_(planes), base_{material.colour[0], material.colour[1], material.colour[2]} {
    if constexpr (kPattern) sampler_ = context.pattern->SamplerAt(lod);
    if constexpr (kSurface == Surface::kShadowed) {
      shadow_ = context.shadow;
      const Eigen::Vector3f sun = shadow_->SunDiffuse(material);
      for (int j = 0; j < 3; ++j) sun_[j] = sun[j];
    }
  }

  /// Whether the pixels come with an alpha that cuts the surface (Shade's `alpha`).
  bool cutout() const { return kSurface == Surface::kCutout; }

  /// The colours at fx[i] pixels from the box's first column on rows where plane k is at(k, i)
  /// in that column, and where cutout(), their alpha 0..1. One loop over the lanes, so that each
  /// step's values stay in vector registers; the loops inside it are unrolled, which vectorising
  /// it needs.
  template <class At>
  void Shade(const At& at, const float fx[kSpanLanes], uint32_t colour[kSpanLanes],
             float alpha[kSpanLanes] = nullptr) const {
    const float* step = planes_.dx;
#pragma omp simd
    for (int i = 0; i < kSpanLanes; ++i) {
      const float w = 1.0f / (at(Planes::kInverseW, i) + step[Planes::kInverseW] * fx[i]);
      float c[kChannels];
#pragma GCC unroll 8
      for (int k = 0; k < kChannels; ++k) {
        c[k] = (at(Planes::kChannel + k, i) + step[Planes::kChannel + k] * fx[i]) * w;
      }
      float base[3] = {base_[0], base_[1], base_[2]};
      if constexpr (kSurface == Surface::kPatterned) {
        float texel[3];
        sampler_.Sample(c[6], c[7], texel);
#pragma GCC unroll 3
        for (int j = 0; j < 3; ++j) base[j] *= texel[j];
      }
      if constexpr (kSurface == Surface::kCutout) {
        float texel[3];
        sampler_.SampleStraight(c[6], c[7], texel, &alpha[i]);
#pragma GCC unroll 3
        for (int j = 0; j < 3; ++j) base[j] *= texel[j];
      }
      if constexpr (kSurface == Surface::kShadowed) {
        const float shadow = shadow_->At(c[6], c[7]);
#pragma GCC unroll 3
        for (int j = 0; j < 3; ++j) {
          c[j] -= shadow * sun_[j];
          c[3 + j] *= 1.0f - shadow;
        }
      }
      colour[i] = PackRgbx(EncodeSrgb(base[0] * c[0] + c[3]), EncodeSrgb(base[1] * c[1] + c[4]),
                           EncodeSrgb(base[2] * c[2] + c[5]));
    }
  }

 private:
  const Planes& planes_;
  float base_[3];
  FilteredTexture::Sampler sampler_;      ///< kPatterned, kCutout: the triangle's levels
  const GroundShadow* shadow_ = nullptr;  ///< kShadowed
  float sun_[3] = {};                     ///< kShadowed: Dsun
};

/// Phong: channels are world position (0-2) and normal (3-5); Blinn-Phong per pixel, with the
/// material's colour times the filtered pattern when patterned. The same Shade as BlockShader's,
/// a pixel at a time: per-pixel lighting does not vectorise as the interpolated light does.
class PhongShader {
 public:
  PhongShader(const TriangleSetup& t, const ShadeContext& context, const Planes& planes)
      : t_(t), context_(context), planes_(planes), material_(context.scene->materials[t.material]) {
    if (material_.patterned)
      sampler_ = context.pattern->SamplerAt(context.pattern->LevelOfDetail(t.uv_area_per_pixel));
    cutout_ = material_.patterned && context.pattern->has_alpha();
    shadowed_ = material_.receives_shadow && context.shadow != nullptr && !context.shadow->empty();
    if (shadowed_) sun_ = context.shadow->SunDiffuse(material_);
  }

  bool cutout() const { return cutout_; }

  /// The colour fx pixels from the box's first column on a row where plane k is at(k) there,
  /// and where cutout(), its alpha into *alpha.
  template <class At>
  uint32_t ShadePixel(const At& at, float fx, float* alpha = nullptr) const {
    const auto value = [&](int k) { return at(k) + planes_.dx[k] * fx; };
    const float w = 1.0f / value(Planes::kInverseW);
    float c[kPlaneChannels];
    for (int k = 0; k < kPlaneChannels; ++k) c[k] = value(Planes::kChannel + k) * w;
    Eigen::Vector3f normal = Eigen::Vector3f(c[3], c[4], c[5]).normalized();
    if (t_.back_facing) normal = -normal;
    const render::Shade shade = ShadePoint(material_, context_.scene->lighting,
                                           Eigen::Vector3f(c[0], c[1], c[2]), normal, context_.eye);
    Eigen::Vector3f base = material_.colour;
    if (material_.patterned) {
      float texel[3];
      if (cutout_) {
        sampler_.SampleStraight(c[6], c[7], texel, alpha);
      } else {
        sampler_.Sample(c[6], c[7], texel);
      }
      base = base.cwiseProduct(Eigen::Vector3f(texel[0], texel[1], texel[2]));
    }
    Eigen::Vector3f diffuse = shade.diffuse, specular = shade.specular;
    if (shadowed_) {  // as BlockShader's kShadowed, at the ground point (x, z) = (u, v)
      const float shadow = context_.shadow->At(c[0], c[2]);
      diffuse -= shadow * sun_;
      specular *= 1.0f - shadow;
    }
    const Eigen::Vector3f colour = base.cwiseProduct(diffuse) + specular;
    return PackRgbx(EncodeSrgb(colour[0]), EncodeSrgb(colour[1]), EncodeSrgb(colour[2]));
  }

  /// BlockShader's interface: a block of pixels at fx[i].
  template <class At>
  void Shade(const At& at, const float fx[kSpanLanes], uint32_t colour[kSpanLanes],
             float alpha[kSpanLanes] = nullptr) const {
    for (int i = 0; i < kSpanLanes; ++i)
      colour[i] = ShadePixel([&](int k) { return at(k, i); }, fx[i], alpha != nullptr ? &alpha[i] : nullptr);
  }

 private:
  const TriangleSetup& t_;
  const ShadeContext& context_;
  const Planes& planes_;
  const Material& material_;
  FilteredTexture::Sampler sampler_;               ///< when patterned: the triangle's levels
  bool shadowed_ = false;                          ///< in the ground's shadow
  bool cutout_ = false;                            ///< the pattern's alpha cuts the surface
  Eigen::Vector3f sun_ = Eigen::Vector3f::Zero();  ///< when shadowed: Dsun
};

/// Whether a receiving triangle's pixels [x0, x1] x [y0, y1] may show ground in shadow: the
/// (u, v) = (x, z) at the box's corners (channels 6, 7 over 1 / w), whose box holds all the box
/// shows of a plane.
inline bool BoxMayBeShadowed(const TriangleSetup& t, const GroundShadow& shadow, int x0, int y0, int x1,
                             int y1) {
  if (shadow.empty()) return false;
  float low[2] = {INFINITY, INFINITY}, high[2] = {-INFINITY, -INFINITY};
  for (const int x : {x0, x1}) {
    for (const int y : {y0, y1}) {
      const float fx = float(x - t.min_x), fy = float(y - t.min_y);
      const auto at = [&](const Plane& p) { return p.origin + p.dx * fx + p.dy * fy; };
      const float w = 1.0f / at(t.inverse_w);
      for (int k = 0; k < 2; ++k) {
        const float value = at(t.channels[6 + k]) * w;
        low[k] = std::min(low[k], value);
        high[k] = std::max(high[k], value);
      }
    }
  }
  return shadow.Touches(low[0], low[1], high[0], high[1]);
}

/// Calls fill(shader) with the shader for triangle t in the context's mode, over the box of
/// pixels [x0, x1] x [y0, y1] of a tile: BlockShader for flat and Gouraud, of the material's
/// surface (kCutout for a pattern with transparent texels; kShadowed only where the box's ground may be in
/// shadow: its corners' (u, v) span the ground it shows, a projective image of the box), PhongShader for
/// Phong.
template <class Fill>
void WithShader(const TriangleSetup& t, const ShadeContext& context, const Planes& planes, int x0, int y0,
                int x1, int y1, const Fill& fill) {
  const Material& material = context.scene->materials[t.material];
  if (context.mode == ShadingMode::kPhong) {
    fill(PhongShader(t, context, planes));
  } else if (material.patterned && context.pattern->has_alpha()) {
    fill(BlockShader<Surface::kCutout>(planes, material, context,
                                       context.pattern->LevelOfDetail(t.uv_area_per_pixel)));
  } else if (material.patterned) {
    fill(BlockShader<Surface::kPatterned>(planes, material, context,
                                          context.pattern->LevelOfDetail(t.uv_area_per_pixel)));
  } else if (material.receives_shadow && context.shadow != nullptr &&
             BoxMayBeShadowed(t, *context.shadow, x0, y0, x1, y1)) {
    fill(BlockShader<Surface::kShadowed>(planes, material, context));
  } else {
    fill(BlockShader<Surface::kPlain>(planes, material, context));
  }
}

}  // namespace flagsim::render
