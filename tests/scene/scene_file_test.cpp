#include "server/scene/scene_file.hpp"

#include <gtest/gtest.h>

#include "server/scene/scene_timeline.hpp"

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
  EXPECT_EQ(breeze.sim.forces.stiffness, defaults.sim.forces.stiffness);
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
  EXPECT_EQ(scene.sim.forces.stiffness, 3000);
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
  // Checked as WIND is, with the table's path and the key's line.
  EXPECT_EQ(ErrorOf("[wind]\ngust = 0.2\nvelocity = [100, 0, 0]\n"),
            "test.toml:3: wind.velocity: speed 100 m/s is out of range; allowed 0 .. 60 m/s");
  EXPECT_EQ(ErrorOf("[wind]\nvelocity = [1, 0, 0]\ngust = 2\n"),
            "test.toml:3: wind.gust: 2 is out of range; allowed 0 .. 1");
  EXPECT_EQ(ErrorOf("[wind]\nramp_time = 100\n"),
            "test.toml:2: wind.ramp_time: 100 is out of range; allowed 0 .. 60 s");
  EXPECT_NE(ErrorOf("[wind]\nspeed = 3\n").find("unknown key wind.speed"), std::string::npos);
  EXPECT_EQ(ErrorOf("name = \n").rfind("test.toml:1:", 0), 0u);  // TOML syntax
  EXPECT_NE(ErrorOf("[parameters]\nintegrator = \"seed\"\nfriction = 2\n").find("seed integrator"),
            std::string::npos);
  EXPECT_NE(ErrorOf("settle = -1\n").find("settle must be a number of seconds, 0 .. 60"), std::string::npos);
  EXPECT_NE(ErrorOf("settle = \"long\"\n").find("settle must be"), std::string::npos);
  EXPECT_EQ(ParseScene("settle = 2.5\n", "test.toml").settle, 2.5);
}

/// The error has `expected` in it.
void ExpectError(const std::string& error, const std::string& expected) {
  EXPECT_NE(error.find(expected), std::string::npos) << "'" << error << "' lacks '" << expected << "'";
}

TEST(SceneFile, ADesignIsChosenByNameAtTheTopLevel) {
  EXPECT_EQ(ParseScene("design = \"tricolour\"\n", "test.toml").service.design,
            render::FlagDesign::kTricolour);
  EXPECT_EQ(ParseScene("name = \"x\"\n", "test.toml").service.design, render::FlagDesign::kNordicCross);
  EXPECT_EQ(
      ErrorOf("design = \"union_jack\"\n"),
      "test.toml:1: design: 'union_jack' is neither a built-in design (nordic_cross, tricolour, checker) nor "
      "an image file: cannot read union_jack: No such file or directory");
  EXPECT_EQ(ErrorOf("design = 3\n"),
            "test.toml:1: design must be a string: a built-in design's name or an image's path");
  ExpectError(ErrorOf("design = \"image\"\n"), "cannot read image");
}

TEST(SceneFile, ReadsATimeline) {
  const Scene scene = ParseScene(R"(
[timeline]
play = true
loop = true
speed = 0.5
[[timeline.keys]]
time = 4
wind = [0.0, 0.0, -8.0]
camera = { eye = [1, 2, 5], target = [0.8, 2, 0], fov = 45 }
[[timeline.keys]]
time = 0
law = "cubic"
wind = [6, 0, 0]
gust = 0.2
parameters = { stiffness = 1500, gravity = 9 }
)",
                                 "test.toml");
  const sim::Timeline& timeline = scene.timeline;
  EXPECT_TRUE(timeline.playing());
  EXPECT_TRUE(timeline.loop());
  EXPECT_EQ(timeline.speed(), 0.5);
  ASSERT_EQ(timeline.keys().size(), 2u);
  const sim::Keyframe& first = timeline.keys()[0];  // in time order, whatever the file's
  EXPECT_EQ(first.time, 0);
  EXPECT_EQ(first.law, sim::ControlLaw::kCubic);
  EXPECT_EQ(first.wind->velocity, (sim::Vec3{6, 0, 0}));
  EXPECT_EQ(first.wind->gust, 0.2);
  EXPECT_EQ(*first.Parameter("stiffness"), 1500);
  EXPECT_EQ(*first.Parameter("gravity"), 9);
  EXPECT_FALSE(first.camera);
  const sim::Keyframe& second = timeline.keys()[1];
  EXPECT_EQ(second.law, sim::ControlLaw::kLinear);  // the default
  EXPECT_EQ(second.wind->gust, 0);
  ASSERT_TRUE(second.camera);
  EXPECT_EQ(second.camera->eye, (sim::Vec3{1, 2, 5}));
  EXPECT_EQ(second.camera->fov, 45);
  EXPECT_TRUE(second.parameters.empty());
}

TEST(SceneFile, TimelineErrorsNameTheKeyFieldAndProblem) {
  const auto error_of_key = [](const std::string& key) { return ErrorOf("[[timeline.keys]]\n" + key); };
  ExpectError(error_of_key("wind = [1, 0, 0]\n"), "test.toml:1: timeline.keys[0].time is missing");
  ExpectError(error_of_key("time = 0\nlaw = \"bezier\"\nwind = [1, 0, 0]\n"),
              "test.toml:3: timeline.keys[0].law must be one of: step, linear, smooth, cubic");
  ExpectError(error_of_key("time = 0\nparameters = { cols = 40 }\n"),
              "timeline.keys[0].parameters.cols: cannot be animated");
  ExpectError(error_of_key("time = 0\nparameters = { stiffness = nan }\n"),
              "timeline.keys[0].parameters.stiffness: nan is not a finite number; allowed 1 .. 1e+05 N/m");
  ExpectError(error_of_key("time = 0\nparameters = { stiffness = true }\n"),
              "timeline.keys[0].parameters.stiffness must be a number");
  ExpectError(error_of_key("time = 0\ngust = 0.3\n"), "gust needs wind");
  ExpectError(error_of_key("time = 0\nwind = [100, 0, 0]\n"), "timeline.keys[0].wind.velocity: speed 100");
  ExpectError(error_of_key("time = 0\ncamera = { eye = [1, 2, 3], target = [0, 2, 0] }\n"),
              "timeline.keys[0].camera needs eye, target and fov; fov is missing");
  ExpectError(error_of_key("time = 0\ncamera = { eye = [1, 2, 3], target = [0, 2, 0], fov = 300 }\n"),
              "timeline.keys[0].camera.fov: 300 is out of range; allowed 10 .. 120 degrees");
  ExpectError(error_of_key("time = -2\nwind = [1, 0, 0]\n"), "timeline.keys[0].time: -2 is out of range");
  ExpectError(error_of_key("time = 1\n"), "timeline.keys[0] sets nothing");
  ExpectError(error_of_key("time = 1\nspeed = 3\n"), "unknown key timeline.keys[0].speed");
  ExpectError(
      ErrorOf("[[timeline.keys]]\ntime = 1\nwind = [1, 0, 0]\n[[timeline.keys]]\ntime = 1\nwind = [2, 0, "
              "0]\n"),
      "timeline.keys[1].time: 1 s already has a key");
  ExpectError(ErrorOf("[timeline]\nspeed = 0\n"), "test.toml: timeline.speed: 0; allowed above 0");
  ExpectError(ErrorOf("[timeline]\nrate = 2\n"), "unknown key timeline.rate");
  ExpectError(ErrorOf("[timeline]\nplay = 1\n"), "timeline.play must be true or false");
  ExpectError(ErrorOf("[timeline]\nkeys = 3\n"), "timeline.keys must be tables");
  std::string many;
  for (size_t i = 0; i <= TimelineLimits::kMaxKeys; ++i)
    many += "[[timeline.keys]]\ntime = " + std::to_string(i) + "\nwind = [1, 0, 0]\n";
  ExpectError(ErrorOf(many), "timeline.keys: 257 of them; allowed at most 256");
  ExpectError(ErrorOf("[parameters]\nintegrator = \"seed\"\n[[timeline.keys]]\ntime = 0\nparameters = { "
                      "friction = 2 }\n"),
              "timeline.friction: the keys reach 2; the seed integrator");
}

TEST(SceneFile, TheSwingExampleLoops) {
  const Scene scene = LoadScene(std::string(FLAGSIM_SOURCE_DIR) + "/scenes/swing.toml");
  const sim::Timeline& timeline = scene.timeline;
  EXPECT_TRUE(timeline.playing());
  EXPECT_TRUE(timeline.loop());
  ASSERT_EQ(timeline.keys().size(), 5u);
  EXPECT_EQ(timeline.End(), 8);
  // The loop joins: its last key sets what its first sets, to the same values.
  EXPECT_EQ(timeline.keys().back().wind, timeline.keys().front().wind);
  EXPECT_EQ(timeline.keys().back().parameters, timeline.keys().front().parameters);
  EXPECT_EQ(timeline.Evaluate(8), timeline.Evaluate(0));
}

TEST(SceneFile, UnknownPathListsThePresets) {
  try {
    LoadScene("/no/such/scene.toml");
    FAIL() << "loaded a missing file";
  } catch (const SceneError& error) {
    EXPECT_NE(std::string(error.what()).find("presets: breeze, calm, gale, hanging"), std::string::npos);
  }
}

// A directory opens as a stream that reads as an empty file: it would be the defaults.
TEST(SceneFile, ADirectoryIsRefused) {
  const std::string directory = std::string(FLAGSIM_SOURCE_DIR) + "/scenes";
  try {
    LoadScene(directory);
    FAIL() << "loaded a directory";
  } catch (const SceneError& error) {
    EXPECT_NE(std::string(error.what()).find("'" + directory + "' is a directory"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace flagsim
