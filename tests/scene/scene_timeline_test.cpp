#include "server/scene/scene_timeline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "server/scene/parameter_table.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

sim::Keyframe Key(double time, std::vector<sim::ParameterControl> parameters) {
  sim::Keyframe key;
  key.time = time;
  key.parameters = std::move(parameters);
  return key;
}

sim::Keyframe CameraKey(sim::Vec3 eye, sim::Vec3 target, double fov_degrees) {
  sim::Keyframe key;
  key.camera = sim::CameraControl{eye, target, fov_degrees};
  return key;
}

sim::Keyframe WindKey(sim::Vec3 velocity, double gust) {
  sim::Keyframe key;
  key.wind = sim::WindControl{velocity, gust};
  return key;
}

/// The reason starts with `field` and a colon.
void ExpectField(const std::string& reason, const std::string& field) {
  EXPECT_EQ(reason.rfind(field + ":", 0), 0u) << "'" << reason << "' does not start with " << field;
}

TEST(SceneTimeline, KeysSetTheForcesCoefficientsOnly) {
  EXPECT_EQ(AnimatableNames(),
            (std::vector<std::string>{"stiffness", "shear_stiffness", "bending_stiffness", "damping", "friction",
                                      "wind_coefficient", "gravity"}));
  for (const Parameter& parameter : ParameterTable::Get().parameters()) {
    const double middle = (parameter.min_value + parameter.max_value) / 2;
    const std::string reason = CheckKeyframe(Key(0, {{parameter.name, middle}}), "key");
    if (parameter.animatable) {
      EXPECT_EQ(reason, "") << parameter.name;
    } else {
      ExpectField(reason, "key.parameters." + parameter.name);
      EXPECT_NE(reason.find("cannot be animated"), std::string::npos) << reason;
    }
  }
}

// Every animatable parameter reaches the simulation through the light path.
TEST(SceneTimeline, EveryAnimatableParameterReachesTheSimulation) {
  for (const Parameter& parameter : ParameterTable::Get().parameters()) {
    if (!parameter.animatable) continue;
    Scene scene;
    const double value = parameter.min_value + (parameter.max_value - parameter.min_value) * 0.37;
    ASSERT_NE(value, parameter.default_value()) << parameter.name;
    sim::Controls controls;
    controls.parameters = {{parameter.name, value}};
    ApplyControls(controls, &scene);
    EXPECT_EQ(parameter.get(scene), value) << parameter.name;
    sim::Simulation<float> simulation(Scene{}.sim, Scene{}.wind);
    simulation.SetControls(scene.sim.forces, scene.wind);
    Scene seen;
    seen.sim = simulation.params();
    EXPECT_EQ(parameter.get(seen), value) << parameter.name;
  }
}

TEST(SceneTimeline, BadKeysNameTheFieldAndWhatIsAllowed) {
  const sim::Vec3 eye{2, 2, 4}, target{0.8, 2.2, 0};
  ExpectField(CheckKeyframe(Key(kNan, {{"stiffness", 1000}}), "key"), "key.time");
  ExpectField(CheckKeyframe(Key(-1, {{"stiffness", 1000}}), "key"), "key.time");
  ExpectField(CheckKeyframe(Key(1e6, {{"stiffness", 1000}}), "key"), "key.time");
  EXPECT_NE(CheckKeyframe(Key(-1, {{"stiffness", 1000}}), "key").find("allowed 0 .. 86400 s"),
            std::string::npos);
  sim::Keyframe lawless = Key(0, {{"stiffness", 1000}});
  lawless.law = static_cast<sim::ControlLaw>(7);
  ExpectField(CheckKeyframe(lawless, "key"), "key.law");
  EXPECT_NE(CheckKeyframe(Key(0, {}), "key").find("key sets nothing"), std::string::npos);

  ExpectField(CheckKeyframe(WindKey({kNan, 0, 0}, 0), "key"), "key.wind.velocity.x");
  ExpectField(CheckKeyframe(WindKey({0, kInf, 0}, 0), "key"), "key.wind.velocity.y");
  ExpectField(CheckKeyframe(WindKey({100, 0, 0}, 0), "key"), "key.wind.velocity");
  ExpectField(CheckKeyframe(WindKey({5, 0, 0}, 2), "key"), "key.wind.gust");
  ExpectField(CheckKeyframe(WindKey({5, 0, 0}, kNan), "key"), "key.wind.gust");

  ExpectField(CheckKeyframe(Key(0, {{"colour", 1}}), "key"), "key.parameters");
  EXPECT_NE(
      CheckKeyframe(Key(0, {{"colour", 1}}), "key").find("unknown parameter 'colour'; animatable: stiffness"),
      std::string::npos);
  EXPECT_NE(CheckKeyframe(Key(0, {{"col\x1b[2J" + std::string(64, 'x'), 1}}), "key")
                .find("unknown parameter 'col\\x1b[2J" + std::string(54, 'x') + "...'"),
            std::string::npos);  // quoted as printable text, cut
  for (const double bad : {kNan, kInf, -kInf, -3.0, 1e9}) {
    const std::string reason = CheckKeyframe(Key(0, {{"stiffness", bad}}), "key");
    ExpectField(reason, "key.parameters.stiffness");
    EXPECT_NE(reason.find("allowed 1 .. 1e+05 N/m"), std::string::npos) << reason;
  }
  ExpectField(CheckKeyframe(Key(0, {{"damping", 0.1}, {"damping", 0.2}}), "key"), "key.parameters.damping");
  std::vector<sim::ParameterControl> many(TimelineLimits::kMaxKeyParameters + 1, {"gravity", 9});
  ExpectField(CheckKeyframe(Key(0, many), "key"), "key.parameters");

  ExpectField(CheckKeyframe(CameraKey({kNan, 0, 0}, target, 40), "key"), "key.camera.eye");
  ExpectField(CheckKeyframe(CameraKey(eye, {0, 2000, 0}, 40), "key"), "key.camera.target");
  ExpectField(CheckKeyframe(CameraKey(eye, target, 200), "key"), "key.camera.fov");
  ExpectField(CheckKeyframe(CameraKey(eye, target, kNan), "key"), "key.camera.fov");
  ExpectField(CheckKeyframe(CameraKey(eye, eye, 40), "key"), "key.camera.target");
  EXPECT_EQ(CheckKeyframe(CameraKey(eye, target, 40), "key"), "");
}

TEST(SceneTimeline, TimelinesAreCheckedWhole) {
  const Scene scene;
  sim::Timeline timeline;
  for (size_t i = 0; i <= TimelineLimits::kMaxKeys; ++i) timeline.Add(Key(double(i), {{"gravity", 9}}));
  ExpectField(CheckTimeline(timeline, scene), "keys");
  timeline.Remove(0);
  EXPECT_EQ(CheckTimeline(timeline, scene), "");
  for (const double speed : {0.0, -1.0, kNan, kInf, 1000.0}) {
    sim::Timeline fast = timeline;
    fast.SetSpeed(speed);
    ExpectField(CheckTimeline(fast, scene), "speed");
  }
  sim::Timeline lost = timeline;
  lost.Seek(kNan);
  ExpectField(CheckTimeline(lost, scene), "position");
}

TEST(SceneTimeline, TheKeysMustSuitTheIntegrator) {
  Scene seed;
  seed.sim.integrator = sim::IntegratorKind::kSeed;
  sim::Timeline timeline;
  timeline.Add(Key(0, {{"friction", 0.5}}));
  EXPECT_EQ(CheckTimeline(timeline, seed), "");
  timeline.Add(Key(1, {{"friction", 1.5}}));
  ExpectField(CheckTimeline(timeline, seed), "friction");
  EXPECT_EQ(CheckTimeline(timeline, Scene{}), "");  // air friction of 1.5/s is fine elsewhere

  // Explicit Euler is stable only by damping: undamped stiff keys would need millions of substeps.
  Scene explicit_euler;
  explicit_euler.sim.integrator = sim::IntegratorKind::kExplicitEuler;
  sim::Timeline stiff;
  stiff.Add(Key(0, {{"stiffness", 2000}}));
  stiff.Add(Key(2, {{"stiffness", 100000}, {"damping", 0}}));
  const std::string reason = CheckTimeline(stiff, explicit_euler);
  ExpectField(reason, "keys");
  EXPECT_NE(reason.find("explicit_euler needs"), std::string::npos) << reason;
  EXPECT_EQ(CheckTimeline(stiff, Scene{}), "");  // symplectic Euler takes it in a few dozen
}

TEST(SceneTimeline, ControlsReachTheSceneWithinTheirLimits) {
  Scene scene;
  const render::Camera before = scene.camera;
  sim::Controls controls;
  controls.wind = sim::WindControl{{0, 0, -100}, 1.5};  // a cubic's overshoot, say
  controls.parameters = {{"stiffness", -50}, {"gravity", 3}};
  controls.camera = sim::CameraControl{{1, 2, 3}, {1, 2, 3}, 172};  // eye on target
  ApplyControls(controls, &scene);
  EXPECT_EQ(scene.wind.velocity, (sim::Vec3{0, 0, -ParameterTable::kMaxWindSpeed}));
  EXPECT_EQ(scene.wind.gust, ParameterTable::kMaxGust);
  EXPECT_EQ(scene.wind.ramp_time, 0);
  EXPECT_EQ(scene.sim.forces.stiffness, ParameterTable::Get().Find("stiffness")->min_value);
  EXPECT_EQ(scene.sim.forces.gravity, 3);
  EXPECT_EQ(scene.camera.eye, before.eye);  // kept: a view from the target sees nothing
  EXPECT_DOUBLE_EQ(scene.camera.fov_y, TimelineLimits::kMaxFov * M_PI / 180);

  controls.camera = sim::CameraControl{{1, 2, 3}, {0, 2, 0}, 30};
  ApplyControls(controls, &scene);
  EXPECT_EQ(scene.camera.eye, Eigen::Vector3d(1, 2, 3));
  EXPECT_DOUBLE_EQ(scene.camera.fov_y, M_PI / 6);
}

TEST(SceneTimeline, ControlsInForceAreTheScenes) {
  Scene scene;
  scene.sim.forces.stiffness = 1234;
  sim::Timeline timeline;
  sim::Keyframe key = Key(0, {{"stiffness", 3000}});
  key.camera = sim::CameraControl{{1, 2, 3}, {0, 2, 0}, 30};
  timeline.Add(key);
  const sim::Controls in_force = ControlsInForce(scene, timeline, sim::WindControl{{1, 2, 3}, 0.1});
  ASSERT_EQ(in_force.parameters.size(), 1u);
  EXPECT_EQ(in_force.parameters[0].value, 1234);
  EXPECT_FALSE(in_force.wind);  // the timeline does not set it
  ASSERT_TRUE(in_force.camera);
  EXPECT_EQ(in_force.camera->eye[2], scene.camera.eye.z());
  EXPECT_DOUBLE_EQ(in_force.camera->fov, scene.camera.fov_y * 180 / M_PI);
}

TEST(SceneTimeline, SettingsAroundHoldTheSegmentsExtremesWithinTheTable) {
  const Scene scene;
  sim::Timeline timeline;
  timeline.Add(Key(0, {{"stiffness", 1000}, {"damping", 0.2}}));
  timeline.Add(Key(2, {{"stiffness", 3000}, {"damping", 0.1}}));
  const SettingRange around = SettingsAround(scene, timeline, 1);
  EXPECT_EQ(around.least.forces.stiffness, 1000);
  EXPECT_EQ(around.most.forces.stiffness, 3000);
  EXPECT_EQ(around.least.forces.damping, 0.1);
  EXPECT_EQ(around.most.forces.damping, 0.2);
  EXPECT_EQ(around.least.forces.friction, scene.sim.forces.friction);  // not animated: as the scene has it

  // A cubic that dips below the table's least stiffness is held to it.
  sim::Timeline dipping;
  for (const auto& [time, value] : {std::pair{0.0, 1.0}, {2.0, 1.0}, {4.0, 100000.0}}) {
    sim::Keyframe each = Key(time, {{"stiffness", value}});
    each.law = sim::ControlLaw::kCubic;
    dipping.Add(each);
  }
  EXPECT_EQ(SettingsAround(scene, dipping, 1).least.forces.stiffness, 1);
}

TEST(SceneTimeline, OnlySpringsDampingAndFrictionMoveTheSubsteps) {
  sim::Timeline timeline;
  timeline.Add(WindKey({3, 0, 0}, 0));
  timeline.Add(Key(1, {{"gravity", 5}, {"wind_coefficient", 2}}));
  EXPECT_FALSE(MovesStability(timeline));
  timeline.Add(Key(2, {{"damping", 0.1}}));
  EXPECT_TRUE(MovesStability(timeline));
}

}  // namespace
}  // namespace flagsim
