// Drawing a RenderScene with OpenGL's fixed-function pipeline into an offscreen framebuffer, on an
// EGL context without a surface (Mesa's surfaceless platform: llvmpipe when there is no GPU).
// The GL state mirrors flagsim's Gouraud mode (shading.hpp):
//
//   material   ambient ka colour, diffuse kd colour, specular ks (white), shininess
//   lights     ambient 0, diffuse = specular = the light's colour; w = 0 directional, 1 point
//   model      the scene's ambient, local viewer, two-sided, separate specular colour
//   pattern    GL_MODULATE, trilinear (GL_LINEAR_MIPMAP_LINEAR), rows uploaded as stored (t = v,
//              row 0 at v = 0), an sRGB texture (decoded to linear light when sampled)
//   samples    1, or n per pixel (multisampled renderbuffers, resolved by a blit before reading)
//   light      linear: sRGB renderbuffers with GL_FRAMEBUFFER_SRGB, so what is written is encoded
//              as flagsim's tiles encode it (srgb.hpp); the sky is written as the sRGB it is
//
// so that per vertex GL computes colour * D (primary colour) and S (secondary colour), and per
// pixel texel * primary + secondary: flagsim's base * D + S. The sky is a full-screen quad drawn
// first without lighting or depth writes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "server/render/camera.hpp"
#include "server/render/mesh.hpp"

namespace flagsim::bench {

/// An OpenGL compatibility context, current on the thread that opened it, with no surface.
/// The renderer is chosen by Mesa's environment (LP_NUM_THREADS etc.) when Open() runs.
class GlContext {
 public:
  GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;
  ~GlContext();

  /// Opens the surfaceless display, creates a context and makes it current; "" or what went wrong.
  std::string Open();
  /// GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string RendererName() const;

 private:
  void* display_ = nullptr;  ///< EGLDisplay
  void* context_ = nullptr;  ///< EGLContext
};

/// A width x height framebuffer object (sRGB colour, 24-bit depth, one or more samples a
/// pixel) and the scene's pattern as a texture, drawn into with fixed-function lighting. Lives
/// inside a current GlContext.
class GlSceneRenderer {
 public:
  GlSceneRenderer() = default;
  GlSceneRenderer(const GlSceneRenderer&) = delete;
  GlSceneRenderer& operator=(const GlSceneRenderer&) = delete;
  ~GlSceneRenderer();

  /// Creates the framebuffer(s) and the texture and sets the state that stays; "" or what went wrong.
  std::string Init(int width, int height, int samples, const render::Texture& pattern);

  /// (scene, camera) => the frame drawn (vertex arrays sent again), resolved when multisampled,
  /// finished (glFinish) and read into `rgba`: RGBA8, rows bottom to top as GL stores them. The camera's image size must be
  /// Init's.
  void Render(const render::RenderScene& scene, const render::Camera& camera, std::vector<uint8_t>* rgba);

 private:
  void DrawSky(const render::RenderScene& scene) const;
  void LoadCamera(const render::Camera& camera) const;
  void SetLights(const render::Lighting& lighting) const;
  void DrawMesh(const render::RenderScene& scene, const render::Mesh& mesh) const;

  int width_ = 0;                 ///< px
  int height_ = 0;                ///< px
  int samples_ = 1;               ///< per pixel
  unsigned framebuffer_ = 0;      ///< GL framebuffer object drawn into
  unsigned colour_buffer_ = 0;    ///< GL renderbuffer, SRGB8_ALPHA8, samples_ a pixel
  unsigned depth_buffer_ = 0;     ///< GL renderbuffer, DEPTH_COMPONENT24, samples_ a pixel
  unsigned resolved_framebuffer_ = 0;  ///< multisampled: the resolved image, read back
  unsigned resolved_buffer_ = 0;       ///< its GL renderbuffer, SRGB8_ALPHA8
  unsigned pattern_texture_ = 0;  ///< GL texture, RGB8
};

/// RGBA8 rows bottom to top => RGB8 rows top to bottom (flagsim's Framebuffer layout).
std::vector<uint8_t> RgbTopDown(const std::vector<uint8_t>& rgba, int width, int height);

}  // namespace flagsim::bench
