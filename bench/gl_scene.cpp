#include "bench/gl_scene.hpp"

#define EGL_NO_X11  // EGL's native types as plain pointers: no Xlib headers
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstdio>
#include <cstring>

namespace flagsim::bench {
namespace {

// The meshes' arrays go to GL as they are: tightly packed floats and indices.
static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float) && sizeof(Eigen::Vector2f) == 2 * sizeof(float));
static_assert(sizeof(std::array<uint32_t, 3>) == 3 * sizeof(GLuint));

/// The framebuffer-object entry points (GL 3.0), looked up through EGL once a context exists.
struct FramebufferFunctions {
  PFNGLGENFRAMEBUFFERSPROC GenFramebuffers = nullptr;
  PFNGLDELETEFRAMEBUFFERSPROC DeleteFramebuffers = nullptr;
  PFNGLBINDFRAMEBUFFERPROC BindFramebuffer = nullptr;
  PFNGLFRAMEBUFFERRENDERBUFFERPROC FramebufferRenderbuffer = nullptr;
  PFNGLCHECKFRAMEBUFFERSTATUSPROC CheckFramebufferStatus = nullptr;
  PFNGLGENRENDERBUFFERSPROC GenRenderbuffers = nullptr;
  PFNGLDELETERENDERBUFFERSPROC DeleteRenderbuffers = nullptr;
  PFNGLBINDRENDERBUFFERPROC BindRenderbuffer = nullptr;
  PFNGLRENDERBUFFERSTORAGEPROC RenderbufferStorage = nullptr;
  PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC RenderbufferStorageMultisample = nullptr;
  PFNGLBLITFRAMEBUFFERPROC BlitFramebuffer = nullptr;
  PFNGLGENERATEMIPMAPPROC GenerateMipmap = nullptr;
};

FramebufferFunctions gl_framebuffer;

template <typename Function>
bool Load(const char* name, Function* function) {
  *function = reinterpret_cast<Function>(eglGetProcAddress(name));
  return *function != nullptr;
}

bool LoadFramebufferFunctions() {
  FramebufferFunctions& f = gl_framebuffer;
  return Load("glGenFramebuffers", &f.GenFramebuffers) &&
         Load("glDeleteFramebuffers", &f.DeleteFramebuffers) &&
         Load("glBindFramebuffer", &f.BindFramebuffer) &&
         Load("glFramebufferRenderbuffer", &f.FramebufferRenderbuffer) &&
         Load("glCheckFramebufferStatus", &f.CheckFramebufferStatus) &&
         Load("glGenRenderbuffers", &f.GenRenderbuffers) &&
         Load("glDeleteRenderbuffers", &f.DeleteRenderbuffers) &&
         Load("glBindRenderbuffer", &f.BindRenderbuffer) &&
         Load("glRenderbufferStorage", &f.RenderbufferStorage) &&
         Load("glRenderbufferStorageMultisample", &f.RenderbufferStorageMultisample) &&
         Load("glBlitFramebuffer", &f.BlitFramebuffer) && Load("glGenerateMipmap", &f.GenerateMipmap);
}

std::string EglError(const std::string& what) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", unsigned(eglGetError()));
  return what + " failed (EGL error " + code + ")";
}

/// (rgb, alpha 1) as GL's four floats.
struct Rgba {
  GLfloat value[4];
};

Rgba ToRgba(const Eigen::Vector3f& rgb) { return Rgba{{rgb[0], rgb[1], rgb[2], 1.0f}}; }

/// A flagsim material as GL's material terms on `face` (GL_FRONT or GL_BACK).
void SetMaterial(GLenum face, const render::Material& material) {
  const Rgba ambient = ToRgba(material.ambient * material.colour);
  const Rgba diffuse = ToRgba(material.diffuse * material.colour);
  const Rgba specular = ToRgba(Eigen::Vector3f::Constant(material.specular));
  glMaterialfv(face, GL_AMBIENT, ambient.value);
  glMaterialfv(face, GL_DIFFUSE, diffuse.value);
  glMaterialfv(face, GL_SPECULAR, specular.value);
  glMaterialf(face, GL_SHININESS, material.shininess);
}

/// Lighting model, depth test and the pattern's sampling: the state every frame shares.
void SetFixedState() {
  glDisable(GL_DITHER);
  glEnable(GL_NORMALIZE);
  glDepthFunc(GL_LESS);
  glClearDepth(1.0);
  glFrontFace(GL_CCW);
  glCullFace(GL_BACK);
  glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, GL_TRUE);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
  glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, GL_SEPARATE_SPECULAR_COLOR);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
}

}  // namespace

// ---- GlContext -----------------------------------------------------------------------------

GlContext::~GlContext() {
  if (display_ == nullptr) return;
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (context_ != nullptr) eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

// (Mesa's environment) => display, compatibility context current with no surface
std::string GlContext::Open() {
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display = nullptr;
  if (!Load("eglGetPlatformDisplayEXT", &get_platform_display)) return "no eglGetPlatformDisplayEXT";
  display_ = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display_ == EGL_NO_DISPLAY) return EglError("eglGetPlatformDisplayEXT(surfaceless)");
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display_, &major, &minor)) {
    display_ = nullptr;
    return EglError("eglInitialize");
  }
  if (!eglBindAPI(EGL_OPENGL_API)) return EglError("eglBindAPI(OpenGL)");
  // Any config that renders OpenGL; surface type 0 matches them all (there are no windows here).
  const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(display_, config_attributes, &config, 1, &configs) || configs < 1) {
    return EglError("eglChooseConfig(OpenGL)");
  }
  // No version asked: Mesa gives its highest compatibility-profile version.
  context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, nullptr);
  if (context_ == EGL_NO_CONTEXT) return EglError("eglCreateContext");
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) return EglError("eglMakeCurrent");
  if (!LoadFramebufferFunctions()) return "framebuffer object functions missing";
  return "";
}

std::string GlContext::RendererName() const {
  const GLubyte* name = glGetString(GL_RENDERER);
  return name != nullptr ? reinterpret_cast<const char*>(name) : "";
}

// ---- GlSceneRenderer -----------------------------------------------------------------------

GlSceneRenderer::~GlSceneRenderer() {
  for (const unsigned framebuffer : {framebuffer_, resolved_framebuffer_}) {
    if (framebuffer != 0) gl_framebuffer.DeleteFramebuffers(1, &framebuffer);
  }
  for (const unsigned renderbuffer : {colour_buffer_, depth_buffer_, resolved_buffer_}) {
    if (renderbuffer != 0) gl_framebuffer.DeleteRenderbuffers(1, &renderbuffer);
  }
  if (pattern_texture_ != 0) glDeleteTextures(1, &pattern_texture_);
}

// (size, samples, pattern) => framebuffer objects bound, pattern texture, fixed state
std::string GlSceneRenderer::Init(int width, int height, int samples, const render::Texture& pattern) {
  const FramebufferFunctions& f = gl_framebuffer;
  width_ = width;
  height_ = height;
  samples_ = samples;
  const auto storage = [&](unsigned* renderbuffer, GLenum format, int count) {
    f.GenRenderbuffers(1, renderbuffer);
    f.BindRenderbuffer(GL_RENDERBUFFER, *renderbuffer);
    if (count > 1) {
      f.RenderbufferStorageMultisample(GL_RENDERBUFFER, count, format, width, height);
    } else {
      f.RenderbufferStorage(GL_RENDERBUFFER, format, width, height);
    }
  };
  const auto attach = [&](unsigned* framebuffer, unsigned colour, unsigned depth) {
    f.GenFramebuffers(1, framebuffer);
    f.BindFramebuffer(GL_FRAMEBUFFER, *framebuffer);
    f.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
    if (depth != 0) f.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    return f.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  };
  if (samples > 1) {  // the resolved image: one sample a pixel, read back
    storage(&resolved_buffer_, GL_SRGB8_ALPHA8, 1);
    if (!attach(&resolved_framebuffer_, resolved_buffer_, 0)) return "resolve framebuffer incomplete";
  }
  storage(&colour_buffer_, GL_SRGB8_ALPHA8, samples);
  storage(&depth_buffer_, GL_DEPTH_COMPONENT24, samples);
  if (!attach(&framebuffer_, colour_buffer_, depth_buffer_)) return "framebuffer incomplete";
  glDrawBuffer(GL_COLOR_ATTACHMENT0);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glViewport(0, 0, width, height);
  if (samples > 1) glEnable(GL_MULTISAMPLE);

  // Rows as stored: GL puts the first row at t = 0, which is flagsim's v = 0 (the top edge).
  // Trilinear, as flagsim's tiles sample it (texture_filter.hpp).
  glGenTextures(1, &pattern_texture_);
  glBindTexture(GL_TEXTURE_2D, pattern_texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8, pattern.width, pattern.height, 0, GL_RGB, GL_UNSIGNED_BYTE,
               pattern.rgb.data());
  f.GenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

  SetFixedState();
  return glGetError() == GL_NO_ERROR ? "" : "GL error while setting up";
}

// (scene, camera) => sky, meshes in order, finished and read back bottom row first
void GlSceneRenderer::Render(const render::RenderScene& scene, const render::Camera& camera,
                             std::vector<uint8_t>* rgba) {
  glClear(GL_DEPTH_BUFFER_BIT);  // the sky covers every pixel's colour
  glDisable(GL_FRAMEBUFFER_SRGB);  // the sky's colours are sRGB already, as flagsim's rows are
  DrawSky(scene);
  glEnable(GL_FRAMEBUFFER_SRGB);  // light is linear: encoded as written, blended and resolved in light
  LoadCamera(camera);
  SetLights(scene.lighting);
  glEnable(GL_LIGHTING);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  for (const render::Mesh& mesh : scene.meshes) DrawMesh(scene, mesh);
  if (samples_ > 1) {  // each pixel the mean of its samples, into the framebuffer read back
    const FramebufferFunctions& f = gl_framebuffer;
    f.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
    f.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved_framebuffer_);
    f.BlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    f.BindFramebuffer(GL_READ_FRAMEBUFFER, resolved_framebuffer_);
  }
  glFinish();
  rgba->resize(size_t(width_) * height_ * 4);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, rgba->data());
  if (samples_ > 1) gl_framebuffer.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
}

// sky colours => a quad over the whole image. Flagsim gives row y (top 0) the colour
// top + y / (height - 1) (horizon - top) at its centre; the quad's edges, half a row beyond the
// first and last centres, get that line continued, so GL's interpolation at pixel centres agrees.
void GlSceneRenderer::DrawSky(const render::RenderScene& scene) const {
  const Eigen::Vector3f step = height_ > 1
                                   ? Eigen::Vector3f((scene.sky_horizon - scene.sky_top) / float(height_ - 1))
                                   : Eigen::Vector3f::Zero();
  const Eigen::Vector3f top_edge = scene.sky_top - 0.5f * step;
  const Eigen::Vector3f bottom_edge = scene.sky_horizon + 0.5f * step;
  glDisable(GL_LIGHTING);
  glDisable(GL_TEXTURE_2D);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDepthMask(GL_FALSE);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glBegin(GL_TRIANGLE_STRIP);
  glColor3fv(top_edge.data());
  glVertex2f(-1, 1);
  glVertex2f(1, 1);
  glColor3fv(bottom_edge.data());
  glVertex2f(-1, -1);
  glVertex2f(1, -1);
  glEnd();
}

// camera => projection and modelview (column-major doubles, as Eigen stores them)
void GlSceneRenderer::LoadCamera(const render::Camera& camera) const {
  const Eigen::Matrix4d projection = camera.Projection(), view = camera.View();
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(projection.data());
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(view.data());
}

// lighting => scene ambient and GL lights, positions given in the world (the modelview is the
// view, so GL keeps them in eye space where it lights)
void GlSceneRenderer::SetLights(const render::Lighting& lighting) const {
  const Rgba ambient = ToRgba(lighting.ambient);
  const Rgba none = ToRgba(Eigen::Vector3f::Zero());
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient.value);
  GLint max_lights = 8;
  glGetIntegerv(GL_MAX_LIGHTS, &max_lights);
  for (int i = 0; i < max_lights; ++i) {
    const GLenum light = GL_LIGHT0 + i;
    if (i >= int(lighting.lights.size())) {
      glDisable(light);
      continue;
    }
    const render::Light& source = lighting.lights[i];
    const Rgba colour = ToRgba(source.colour);
    const GLfloat w = source.kind == render::Light::kDirectional ? 0.0f : 1.0f;
    const GLfloat position[4] = {source.vector[0], source.vector[1], source.vector[2], w};
    glLightfv(light, GL_AMBIENT, none.value);
    glLightfv(light, GL_DIFFUSE, colour.value);
    glLightfv(light, GL_SPECULAR, source.specular ? colour.value : none.value);
    glLightfv(light, GL_POSITION, position);
    glEnable(light);
  }
}

// mesh => its materials (back: the back material, or unused when culled), culling, pattern,
// then its arrays drawn from client memory (GL copies them at the draw, every frame)
void GlSceneRenderer::DrawMesh(const render::RenderScene& scene, const render::Mesh& mesh) const {
  if (mesh.triangles.empty()) return;
  const render::Material& front = scene.materials[mesh.front_material];
  const bool two_sided = mesh.back_material >= 0;
  SetMaterial(GL_FRONT, front);
  SetMaterial(GL_BACK, two_sided ? scene.materials[mesh.back_material] : front);
  if (two_sided) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
  }
  // GL samples per mesh, not per side: the front material decides for both.
  if (front.patterned) {
    glEnable(GL_TEXTURE_2D);
    glEnableClientState(GL_TEXTURE_COORD_ARRAY);
    glTexCoordPointer(2, GL_FLOAT, sizeof(Eigen::Vector2f), mesh.uvs.data());
  } else {
    glDisable(GL_TEXTURE_2D);
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  }
  glVertexPointer(3, GL_FLOAT, sizeof(Eigen::Vector3f), mesh.positions.data());
  glNormalPointer(GL_FLOAT, sizeof(Eigen::Vector3f), mesh.normals.data());
  glDrawElements(GL_TRIANGLES, GLsizei(mesh.triangles.size() * 3), GL_UNSIGNED_INT, mesh.triangles.data());
}

// RGBA rows bottom first => RGB rows top first
std::vector<uint8_t> RgbTopDown(const std::vector<uint8_t>& rgba, int width, int height) {
  std::vector<uint8_t> rgb(size_t(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    const uint8_t* from = &rgba[size_t(height - 1 - y) * width * 4];
    uint8_t* to = &rgb[size_t(y) * width * 3];
    for (int x = 0; x < width; ++x) std::memcpy(to + 3 * x, from + 4 * x, 3);
  }
  return rgb;
}

}  // namespace flagsim::bench
