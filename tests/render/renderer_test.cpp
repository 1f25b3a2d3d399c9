#include "server/render/renderer.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "server/render/srgb.hpp"

namespace flagsim::render {
namespace {

/// The default scene with a wavy flag of cols x rows nodes.
RenderScene WavyFlagScene(int cols = 32, int rows = 24) {
  RenderScene scene = DefaultRenderScene(3.0f);
  std::vector<float> x, y, z;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const float u = float(c) / (cols - 1), v = float(r) / (rows - 1);
      x.push_back(1.5f * u);
      y.push_back(2.98f - 1.0f * v - 0.1f * u * u);
      z.push_back(0.15f * u * std::sin(9 * u + 2 * v));
    }
  }
  UpdateFlagMesh(cols, rows, x.data(), y.data(), z.data(), &scene.meshes[0]);
  return scene;
}

Camera SmallCamera() {
  Camera camera;
  camera.width = 160;
  camera.height = 90;
  return camera;
}

TEST(Renderer, SameImageAtAnyThreadCount) {
  const RenderScene scene = WavyFlagScene();
  Renderer renderer;
  for (const Antialiasing antialiasing : {Antialiasing::kOff, Antialiasing::kMsaa4}) {
    for (const ShadingMode mode :
         {ShadingMode::kWireframe, ShadingMode::kFlat, ShadingMode::kGouraud, ShadingMode::kPhong}) {
      Camera camera;  // full size: many tiles
      Framebuffer reference;
      RenderOptions options;
      options.mode = mode;
      options.antialiasing = antialiasing;
      renderer.Render(scene, camera, options, &reference);
      for (const int threads : {2, 3}) {
        options.threads = threads;
        Framebuffer framebuffer;
        renderer.Render(scene, camera, options, &framebuffer);
        EXPECT_EQ(framebuffer.rgb, reference.rgb)
            << int(mode) << " " << AntialiasingNames()[int(antialiasing)] << " at " << threads << " threads";
      }
    }
  }
}

// A mesh drawn in passes of two chunks (a dozen passes, neighbouring rows of the flag sharing
// tiles across them) gives the image and the depth of one pass, bit for bit.
TEST(Renderer, PassesOfSmallBatchesDrawTheImageOfOnePass) {
  const RenderScene scene = WavyFlagScene(64, 48);
  Renderer renderer;
  for (const auto& [mode, antialiasing] :
       {std::pair{ShadingMode::kFlat, Antialiasing::kOff}, std::pair{ShadingMode::kGouraud, Antialiasing::kOff},
        std::pair{ShadingMode::kPhong, Antialiasing::kOff}, std::pair{ShadingMode::kGouraud, Antialiasing::kMsaa4},
        std::pair{ShadingMode::kPhong, Antialiasing::kMsaa2}}) {
    Camera camera;
    RenderOptions options;
    options.mode = mode;
    options.antialiasing = antialiasing;
    options.keep_depth = true;
    Framebuffer whole, passes;
    renderer.Render(scene, camera, options, &whole);
    const size_t drawn = renderer.triangles_drawn();
    for (const int threads : {1, 2}) {
      options.threads = threads;
      options.batch_triangles = 600;  // two chunks: a dozen passes
      renderer.Render(scene, camera, options, &passes);
      EXPECT_EQ(passes.rgb, whole.rgb) << int(mode) << " at " << threads << " threads";
      EXPECT_EQ(passes.depth, whole.depth) << int(mode) << " at " << threads << " threads";
      EXPECT_EQ(renderer.triangles_drawn(), drawn);
    }
  }
}

TEST(Renderer, AChangedPatternIsDrawnInTheNextFrame) {
  RenderScene scene = WavyFlagScene();
  Renderer renderer;
  const RenderOptions options;
  Framebuffer before, after, fresh;
  renderer.Render(scene, SmallCamera(), options, &before);
  scene.pattern = MakePattern(FlagDesign::kChecker, scene.pattern.width, scene.pattern.height);
  renderer.Render(scene, SmallCamera(), options, &after);
  Renderer().Render(scene, SmallCamera(), options, &fresh);
  EXPECT_NE(after.rgb, before.rgb);
  EXPECT_EQ(after.rgb, fresh.rgb);
}

TEST(Renderer, TheFlagIsDrawnInFrontOfTheSky) {
  const RenderScene scene = WavyFlagScene();
  Renderer renderer;
  Framebuffer framebuffer;
  RenderOptions options;
  options.keep_depth = true;
  renderer.Render(scene, SmallCamera(), options, &framebuffer);
  // Project the middle of the flag and check that pixel is cloth (not sky: the sky is bluish
  // and brightest in blue; the cloth's yellow or dark blue differs from the sky gradient).
  const Camera camera = SmallCamera();
  const Eigen::Vector4d clip = camera.Projection() * camera.View() * Eigen::Vector4d(0.75, 2.45, 0.0, 1.0);
  const int px = int((clip.x() / clip.w() + 1) / 2 * camera.width);
  const int py = int((1 - clip.y() / clip.w()) / 2 * camera.height);
  ASSERT_TRUE(px >= 0 && px < camera.width && py >= 0 && py < camera.height);
  EXPECT_LT(framebuffer.depth[size_t(py) * camera.width + px], 1.0f);
  EXPECT_GT(renderer.triangles_drawn(), 1000u);
}

TEST(Renderer, ModesDifferAndPhongIsClosestToGouraud) {
  RenderScene scene = WavyFlagScene(16, 12);  // coarse: the modes' differences show
  scene.meshes.resize(1);                     // the flag alone
  Camera camera;
  camera.width = 640;
  camera.height = 360;
  Renderer renderer;
  Framebuffer images[4];
  for (int mode = 0; mode < 4; ++mode) {
    RenderOptions options;
    options.mode = ShadingMode(mode);
    renderer.Render(scene, camera, options, &images[mode]);
  }
  const auto difference = [&](int a, int b) {
    double sum = 0;
    for (size_t i = 0; i < images[a].rgb.size(); ++i)
      sum += std::abs(int(images[a].rgb[i]) - int(images[b].rgb[i]));
    return sum;
  };
  EXPECT_GT(difference(0, 2), 0);
  EXPECT_GT(difference(1, 2), 0);
  EXPECT_LT(difference(3, 2), difference(3, 1));  // Gouraud approximates Phong better than flat
}

TEST(Renderer, ACameraInsideTheSceneClipsAtTheNearPlane) {
  const RenderScene scene = WavyFlagScene();
  Camera camera = SmallCamera();
  camera.eye = Eigen::Vector3d(0.7, 2.5, 0.02);  // right against the cloth
  camera.target = Eigen::Vector3d(0.7, 2.5, -1.0);
  Renderer renderer;
  Framebuffer one, two;
  RenderOptions options;
  options.keep_depth = true;
  renderer.Render(scene, camera, options, &one);
  options.threads = 2;
  renderer.Render(scene, camera, options, &two);
  EXPECT_EQ(one.rgb, two.rgb);
  for (const float depth : one.depth) {
    EXPECT_GE(depth, 0.0f);
    EXPECT_LE(depth, 1.0f);
  }
}

/// A small reference image made without the rasterizer: a lit square facing the camera covers
/// exactly the pixels whose centres fall inside its projection, each with the colour the
/// lighting model gives it (in sRGB); the rest is sky.
TEST(Renderer, AFacingSquareMatchesItsReferenceImage) {
  RenderScene scene;
  Material paint;
  paint.colour = Eigen::Vector3f(0.8f, 0.5f, 0.2f);
  paint.ambient = 0.3f;
  paint.diffuse = 0.6f;
  paint.specular = 0.0f;
  scene.materials = {paint};
  Light head_on;
  head_on.vector = Eigen::Vector3f(0, 0, 1);  // along the square's normal: n . l = 1 everywhere
  head_on.colour = Eigen::Vector3f(1.0f, 0.9f, 0.8f);
  scene.lighting.lights = {head_on};
  scene.lighting.ambient = Eigen::Vector3f(0.5f, 0.5f, 0.5f);
  Mesh square;
  for (const auto& [x, y] :
       {std::pair{-1.0f, -0.6f}, std::pair{1.0f, -0.6f}, std::pair{1.0f, 0.6f}, std::pair{-1.0f, 0.6f}}) {
    square.positions.emplace_back(x, y, 0.0f);
    square.normals.emplace_back(0.0f, 0.0f, 1.0f);
    square.uvs.emplace_back(0.0f, 0.0f);
  }
  square.triangles = {{0, 1, 2}, {0, 2, 3}};
  scene.meshes = {square};

  Camera camera;
  camera.eye = Eigen::Vector3d(0.013, -0.021, 5.0);  // off-centre: no edge on a pixel centre
  camera.target = Eigen::Vector3d(0.013, -0.021, 0.0);
  camera.width = 48;
  camera.height = 32;
  // Where the square's corners land, in pixels (y down).
  const Eigen::Matrix4d clip_from_world = camera.Projection() * camera.View();
  const auto screen = [&](double x, double y) {
    const Eigen::Vector4d clip = clip_from_world * Eigen::Vector4d(x, y, 0, 1);
    return Eigen::Vector2d((clip.x() / clip.w() + 1) / 2 * camera.width,
                           (1 - clip.y() / clip.w()) / 2 * camera.height);
  };
  const Eigen::Vector2d low = screen(-1.0, 0.6), high = screen(1.0, -0.6);  // top-left, bottom-right
  const Eigen::Vector3f light = paint.ambient * scene.lighting.ambient + paint.diffuse * head_on.colour;
  const Eigen::Vector3f inside = paint.colour.cwiseProduct(light);

  for (const ShadingMode mode : {ShadingMode::kFlat, ShadingMode::kGouraud, ShadingMode::kPhong}) {
    Renderer renderer;
    Framebuffer framebuffer;
    RenderOptions options;
    options.mode = mode;
    renderer.Render(scene, camera, options, &framebuffer);
    int covered = 0;
    for (int y = 0; y < camera.height; ++y) {
      const float t = float(y) / (camera.height - 1);
      const Eigen::Vector3f sky = scene.sky_top + t * (scene.sky_horizon - scene.sky_top);
      for (int x = 0; x < camera.width; ++x) {
        const bool in = x + 0.5 > low.x() && x + 0.5 < high.x() && y + 0.5 > low.y() && y + 0.5 < high.y();
        covered += in;
        // The square's light is linear, encoded to sRGB; the sky's colours are sRGB already.
        for (int k = 0; k < 3; ++k) {
          const long expected = in ? long(EncodeSrgb(inside[k])) : std::lround(255 * sky[k]);
          EXPECT_NEAR(framebuffer.Pixel(x, y)[k], expected, 1)
              << "mode " << int(mode) << " pixel " << x << "," << y;
        }
      }
    }
    EXPECT_GT(covered, 100);
  }
}

TEST(Renderer, ImageSizeFollowsTheCamera) {
  const RenderScene scene = WavyFlagScene();
  Renderer renderer;
  Framebuffer framebuffer;
  Camera camera = SmallCamera();
  camera.width = 77;
  camera.height = 33;
  renderer.Render(scene, camera, RenderOptions{}, &framebuffer);
  EXPECT_EQ(framebuffer.width, 77);
  EXPECT_EQ(framebuffer.rgb.size(), 77u * 33 * 3);
}

}  // namespace
}  // namespace flagsim::render
