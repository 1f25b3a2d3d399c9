#include "server/render/ground_shadow.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "server/render/renderer.hpp"
#include "server/render/srgb.hpp"

namespace flagsim::render {
namespace {

/// A 1 m square, level, centred on (0, height, 0), seen from both sides.
Mesh LevelSquare(float height) {
  Mesh square;
  for (const auto& [x, z] :
       {std::pair{-0.5f, -0.5f}, std::pair{-0.5f, 0.5f}, std::pair{0.5f, 0.5f}, std::pair{0.5f, -0.5f}}) {
    square.positions.emplace_back(x, height, z);
    square.normals.emplace_back(0, 1, 0);
    square.uvs.emplace_back(0, 0);
  }
  square.triangles = {{0, 1, 2}, {0, 2, 3}};
  square.casts_shadow = true;
  return square;
}

/// Grass that receives the shadow under the square, lit by ambient light and one sun towards
/// `to_sun`.
RenderScene SquareOverGround(float height, const Eigen::Vector3f& to_sun) {
  RenderScene scene;
  Material grass;
  grass.colour = Eigen::Vector3f(0.4f, 0.6f, 0.3f);
  grass.specular = 0;
  grass.receives_shadow = true;
  Material paint;
  scene.materials = {grass, paint};
  Mesh ground = GroundMesh(0, 0, 40);
  ground.front_material = 0;
  Mesh square = LevelSquare(height);
  square.front_material = square.back_material = 1;
  scene.meshes = {square, ground};
  Light sun;
  sun.vector = to_sun.normalized();
  sun.colour = Eigen::Vector3f(0.9f, 0.9f, 0.8f);
  scene.lighting.ambient = Eigen::Vector3f(0.3f, 0.3f, 0.35f);
  scene.lighting.lights = {sun};
  scene.shadow_light = 0;
  return scene;
}

TEST(GroundShadow, FallsWhereTheSunProjectsTheCaster) {
  // The sun at 45 degrees over +x: the square 2 m up shades the ground 2 m towards -x.
  GroundShadow shadow;
  shadow.Cast(SquareOverGround(2.0f, Eigen::Vector3f(1, 1, 0)));
  ASSERT_FALSE(shadow.empty());
  EXPECT_NEAR(shadow.At(-2.0f, 0.0f), 1.0f, 1e-6f);    // the middle of the shadow
  EXPECT_NEAR(shadow.At(-2.3f, 0.3f), 1.0f, 1e-6f);    // well inside it
  EXPECT_NEAR(shadow.At(0.0f, 0.0f), 0.0f, 1e-6f);     // right under the square: in the sun
  EXPECT_NEAR(shadow.At(-2.0f, 0.8f), 0.0f, 1e-6f);    // beside it
  EXPECT_NEAR(shadow.At(40.0f, -30.0f), 0.0f, 1e-6f);  // far off the map
  // Across its edge at x = -1.5 the shadow goes from 0 to 1 over a few cm, half at the edge.
  EXPECT_NEAR(shadow.At(-1.5f, 0.0f), 0.5f, 0.2f);
  EXPECT_LT(shadow.At(-1.45f, 0.0f), 0.05f);
  EXPECT_GT(shadow.At(-1.55f, 0.0f), 0.95f);
}

TEST(GroundShadow, NoneWithoutACasterOrWithTheSunDown) {
  RenderScene scene = SquareOverGround(2.0f, Eigen::Vector3f(0, 1, 0));
  GroundShadow shadow;
  scene.meshes[0].casts_shadow = false;
  shadow.Cast(scene);
  EXPECT_TRUE(shadow.empty());
  EXPECT_EQ(shadow.At(0, 0), 0.0f);
  scene = SquareOverGround(2.0f, Eigen::Vector3f(1, -0.2f, 0));  // below the horizon
  shadow.Cast(scene);
  EXPECT_TRUE(shadow.empty());
  scene = SquareOverGround(2.0f, Eigen::Vector3f(0, 1, 0));
  scene.shadow_light = -1;
  shadow.Cast(scene);
  EXPECT_TRUE(shadow.empty());
}

TEST(GroundShadow, TheGroundInShadowHasNoSunlight) {
  // The sun overhead: under the square the ground is lit by the ambient light alone,
  // base * ka * ambient; a metre beyond it by the sun too, base * (ka * ambient + kd * sun).
  const RenderScene scene = SquareOverGround(1.0f, Eigen::Vector3f(0, 1, 0));
  Camera camera;
  camera.width = 320;
  camera.height = 240;
  camera.eye = Eigen::Vector3d(0, 2, 6);
  camera.target = Eigen::Vector3d(0, 0, 0);
  const Material& grass = scene.materials[0];
  const Eigen::Vector3f in_shadow = grass.colour.cwiseProduct(grass.ambient * scene.lighting.ambient);
  const Eigen::Vector3f in_sun =
      in_shadow + grass.colour.cwiseProduct(grass.diffuse * scene.lighting.lights[0].colour);
  for (const ShadingMode mode : {ShadingMode::kGouraud, ShadingMode::kPhong}) {
    for (const Antialiasing antialiasing : {Antialiasing::kOff, Antialiasing::kMsaa4}) {
      RenderOptions options;
      options.mode = mode;
      options.antialiasing = antialiasing;
      Renderer renderer;
      Framebuffer image;
      renderer.Render(scene, camera, options, &image);
      const Eigen::Matrix4d clip_from_world = camera.Projection() * camera.View();
      const auto pixel_of = [&](double x, double z) {
        Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
        EXPECT_TRUE(ToPixel(clip_from_world, camera, x, 0, z, &pixel));
        return image.Pixel(int(pixel.x()), int(pixel.y()));
      };
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(pixel_of(0.1, 0.1)[k], EncodeSrgb(in_shadow[k]), 1) << int(mode) << " channel " << k;
        EXPECT_NEAR(pixel_of(1.5, 0.0)[k], EncodeSrgb(in_sun[k]), 1) << int(mode) << " channel " << k;
      }
    }
  }
}

TEST(GroundShadow, ACutSurfaceCastsTheShadowOfWhatIsLeft) {
  // The square's pattern is transparent on its -z half (v < 1/2, with v = z + 1/2): the sun
  // straight above shades only the +z half under it.
  RenderScene scene = SquareOverGround(2.0f, Eigen::Vector3f(0, 1, 0));
  Mesh& square = scene.meshes[0];
  for (size_t i = 0; i < square.positions.size(); ++i)
    square.uvs[i] = Eigen::Vector2f(square.positions[i].x() + 0.5f, square.positions[i].z() + 0.5f);
  scene.materials[1].patterned = true;
  scene.pattern.width = 1;
  scene.pattern.height = 2;
  scene.pattern.rgb.assign(6, 255);
  scene.pattern.alpha = {0, 255};
  GroundShadow shadow;
  shadow.Cast(scene);
  ASSERT_FALSE(shadow.empty());
  EXPECT_NEAR(shadow.At(0.0f, 0.3f), 1.0f, 1e-6f);   // under the opaque half
  EXPECT_NEAR(shadow.At(0.0f, -0.3f), 0.0f, 1e-6f);  // under the clear half: in the sun
}

TEST(GroundShadow, ATriangleWhoseTopCornerIsOnARowsCentreLine) {
  // The sun overhead; a level triangle 1.5 m across makes the map 2 m across (with its margins),
  // 1/128 m a texel, from z = -1 m. Its top corner, at z = 0.75 - 1/256 m, falls on texel
  // row 223's centre line, 223.5 texels up: that row meets the triangle only at the corner, and
  // it must draw nothing there (before, it took its span's ends as infinite).
  RenderScene scene = SquareOverGround(2.0f, Eigen::Vector3f(0, 1, 0));
  Mesh& triangle = scene.meshes[0];
  triangle.positions = {{-0.75f, 2.0f, -0.75f}, {0.75f, 2.0f, -0.75f}, {0.0f, 2.0f, 0.75f - 1.0f / 256}};
  triangle.normals.assign(3, Eigen::Vector3f(0, 1, 0));
  triangle.uvs.assign(3, Eigen::Vector2f(0, 0));
  triangle.triangles = {{0, 1, 2}};
  GroundShadow shadow;
  shadow.Cast(scene);
  ASSERT_FALSE(shadow.empty());
  EXPECT_NEAR(shadow.At(0.0f, -0.3f), 1.0f, 1e-6f);  // well inside the triangle's shadow
  EXPECT_NEAR(shadow.At(0.5f, 0.5f), 0.0f, 1e-6f);   // beside its top corner: in the sun
}

}  // namespace
}  // namespace flagsim::render
