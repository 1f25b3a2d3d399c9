#include "scene_file.hpp"

#include <gtest/gtest.h>

namespace flagsim {
namespace {

std::string ErrorOf(const std::string& text) {
  try {
    ParseScene(text, "test.toml");
  } catch (const SceneError& error) {
    return error.what();
  }
  return "";
}

TEST(SceneFile, EveryPresetLoads) {
  const std::vector<std::string> names = PresetNames();
  EXPECT_EQ(names, (std::vector<std::string>{"breeze", "calm", "gale", "hanging"}));
  for (const std::string& name : names) EXPECT_EQ(LoadScene(name).name, name);
}

TEST(SceneFile, BreezeIsTheBuiltInDefault) {
  const Scene breeze = LoadScene("breeze"), defaults;
  EXPECT_EQ(breeze.sim.cols, defaults.sim.cols);
  EXPECT_EQ(breeze.sim.rows, defaults.sim.rows);
  EXPECT_EQ(breeze.sim.width, defaults.sim.width);
  EXPECT_EQ(breeze.sim.stiffness, defaults.sim.stiffness);
  EXPECT_EQ(breeze.wind.velocity, defaults.wind.velocity);
  EXPECT_EQ(breeze.wind.gust, defaults.wind.gust);
  EXPECT_EQ(breeze.description, defaults.description);
}

TEST(SceneFile, OverridesParametersAndWind) {
  const Scene scene = ParseScene(R"(
name = "test"
seed = 9
[parameters]
stiffness = 3000
cols = 16
relative_wind = true
integrator = "seed"
[wind]
velocity = [1, 2, 3.5]
gust = 0.1
ramp_time = 2
)",
                                 "test.toml");
  EXPECT_EQ(scene.name, "test");
  EXPECT_EQ(scene.seed, 9u);
  EXPECT_EQ(scene.sim.stiffness, 3000);
  EXPECT_EQ(scene.sim.cols, 16);
  EXPECT_TRUE(scene.sim.relative_wind);
  EXPECT_EQ(scene.sim.integrator, sim::IntegratorKind::kSeed);
  EXPECT_EQ(scene.wind.velocity, (sim::Vec3{1, 2, 3.5}));
  EXPECT_EQ(scene.wind.ramp_time, 2);
}

TEST(SceneFile, ErrorsNameTheFileLineAndProblem) {
  EXPECT_EQ(ErrorOf("[parameters]\nstiffness = -4\n").rfind("test.toml:2: stiffness:", 0), 0u);
  EXPECT_NE(ErrorOf("[parameters]\nbogus = 1\n").find("unknown parameter 'bogus'"), std::string::npos);
  EXPECT_NE(ErrorOf("colour = 1\n").find("unknown key 'colour'"), std::string::npos);
  EXPECT_NE(ErrorOf("[wind]\nvelocity = [1, 2]\n").find("wind.velocity must be [vx, vy, vz]"),
            std::string::npos);
  EXPECT_NE(ErrorOf("[wind]\nvelocity = [100, 0, 0]\n").find("velocity: speed 100"), std::string::npos);
  EXPECT_NE(ErrorOf("[wind]\nspeed = 3\n").find("unknown key wind.speed"), std::string::npos);
  EXPECT_EQ(ErrorOf("name = \n").rfind("test.toml:1:", 0), 0u);  // TOML syntax
  EXPECT_NE(ErrorOf("[parameters]\nintegrator = \"seed\"\nfriction = 2\n").find("seed integrator"),
            std::string::npos);
}

TEST(SceneFile, UnknownPathListsThePresets) {
  try {
    LoadScene("/no/such/scene.toml");
    FAIL() << "loaded a missing file";
  } catch (const SceneError& error) {
    EXPECT_NE(std::string(error.what()).find("presets: breeze, calm, gale, hanging"), std::string::npos);
  }
}

}  // namespace
}  // namespace flagsim
