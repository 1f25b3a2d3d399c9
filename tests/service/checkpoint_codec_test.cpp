// A session snapshot through checkpoint_t and back: the resumed session takes the original's
// steps and draws its frames bit for bit; hostile checkpoints are refused with the field named.
#include "server/service/checkpoint_codec.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "messages/checked_decode.hpp"
#include "messages/publisher.hpp"
#include "server/service/frame_painter.hpp"

namespace flagsim {
namespace {

/// A small flag with a playing timeline that stiffens it and turns the wind, a camera moved by
/// the seed's transforms, and an image small enough to compare whole.
Scene Busy() {
  Scene scene;
  scene.settle = 0.2;  // the start and a reset are the drape
  scene.sim.cols = 12;
  scene.sim.rows = 9;
  scene.camera.width = 96;
  scene.camera.height = 64;
  sim::Keyframe first, second;
  first.time = 0;
  first.wind = sim::WindControl{{5, 0, 1}, 0.2};
  first.parameters = {{"stiffness", 1500}};
  second.time = 1;
  second.law = sim::ControlLaw::kCubic;
  second.wind = sim::WindControl{{-2, 1, 5}, 0.4};
  second.parameters = {{"stiffness", 2500}};
  scene.timeline.Add(first);
  scene.timeline.Add(second);
  scene.timeline.SetLoop(true);
  scene.timeline.Play();
  return scene;
}

/// A session in the middle of things: a wind ramp, a parameter change, a camera move, a key
/// changed during play (so a glide is under way).
Session Started() {
  Session session(Busy());
  for (int i = 0; i < 100; ++i) session.Step();
  EXPECT_EQ(session.ApplyParams({false, {{"friction", "0.4"}}}), "");
  render::CameraMove move;
  move.operation = render::CameraMove::kRotateY;
  move.angle = 0.3;
  EXPECT_EQ(session.ApplyCamera(move), "");
  TimelineEdit edit;
  edit.operation = TimelineEdit::kChange;
  edit.time = 1;
  edit.keep_law = true;
  edit.key.time = 1;
  edit.key.wind = sim::WindControl{{0, 2, 6}, 0.1};
  EXPECT_EQ(session.ApplyTimeline(edit), "");
  for (int i = 0; i < 30; ++i) session.Step();
  EXPECT_TRUE(session.scene().timeline.gliding());
  return session;
}

/// The message as it crosses the wire: encoded, then decoded with every length checked.
checkpoint_t OverTheWire(const checkpoint_t& message) {
  const std::vector<uint8_t> bytes = Publisher::Encode(message);
  std::string error;
  const auto decoded = wire::CheckedDecode<checkpoint_t>(bytes.data(), bytes.size(), bytes.size(), &error);
  EXPECT_TRUE(decoded.has_value()) << error;
  return *decoded;
}

TEST(CheckpointCodec, AResumedSessionStepsAndDrawsAsTheOriginal) {
  Session original = Started();
  SessionSnapshot snapshot;
  ASSERT_EQ(ReadCheckpoint(OverTheWire(MakeCheckpointMessage(original.Snapshot(), "refresh", 1)), &snapshot),
            "");
  Session resumed(snapshot);
  for (int i = 0; i < 600; ++i) {  // past the glide, round the loop, across segments
    original.Step();
    resumed.Step();
  }
  EXPECT_EQ(resumed.simulation().Hash(), original.simulation().Hash());
  EXPECT_EQ(resumed.simulation().state().step, original.simulation().state().step);
  EXPECT_EQ(resumed.scene().timeline, original.scene().timeline);
  EXPECT_EQ(resumed.scene().sim.forces.stiffness, original.scene().sim.forces.stiffness);
  FramePainter painter;
  const std::vector<uint8_t> resumed_rgb = painter.Paint(FrameInput::Of(resumed, 0), 1).rgb;
  EXPECT_EQ(resumed_rgb, painter.Paint(FrameInput::Of(original, 0), 1).rgb);
  // The initial scene came too: a reset goes back to the same place in both.
  EXPECT_EQ(original.ApplyParams({true, {}}), "");
  EXPECT_EQ(resumed.ApplyParams({true, {}}), "");
  for (int i = 0; i < 50; ++i) {
    original.Step();
    resumed.Step();
  }
  EXPECT_EQ(resumed.simulation().Hash(), original.simulation().Hash());
}

TEST(CheckpointCodec, TheMessageSaysWhereAndWhy) {
  Session session = Started();
  const checkpoint_t message = MakeCheckpointMessage(session.Snapshot(), "periodic", 42);
  EXPECT_EQ(message.step, session.simulation().state().step);
  EXPECT_EQ(uint64_t(message.state_hash), session.simulation().Hash());
  EXPECT_EQ(message.reason, "periodic");
  EXPECT_EQ(message.num_nodes, 12 * 9);
  EXPECT_TRUE(message.scene.timeline.gliding);
}

/// A good message with one thing broken by `spoil`: refused, naming `field`, snapshot untouched.
template <class Spoil>
void ExpectRefused(Spoil spoil, const std::string& field) {
  Session session = Started();
  checkpoint_t message = MakeCheckpointMessage(session.Snapshot(), "refresh", 1);
  spoil(message);
  SessionSnapshot snapshot;
  snapshot.timeline_segment = 77;
  const std::string problem = ReadCheckpoint(message, &snapshot);
  EXPECT_NE(problem.find(field), std::string::npos) << problem;
  EXPECT_EQ(snapshot.timeline_segment, 77);
}

TEST(CheckpointCodec, HostileCheckpointsAreRefusedWithTheFieldNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ExpectRefused([](checkpoint_t& m) { m.x.pop_back(); }, "num_nodes");
  ExpectRefused([](checkpoint_t& m) { m.num_nodes = 5; }, "num_nodes");
  ExpectRefused([](checkpoint_t& m) { m.vx[3] = std::numeric_limits<float>::infinity(); }, "not finite");
  ExpectRefused([](checkpoint_t& m) { m.y[0] += 1; }, "state_hash");
  ExpectRefused([](checkpoint_t& m) { m.scene.names[0] = "colour"; }, "colour is not a parameter");
  ExpectRefused([](checkpoint_t& m) { m.scene.names[1] = m.scene.names[0]; }, "comes twice");
  ExpectRefused([](checkpoint_t& m) { m.scene.names.pop_back(); }, "scene.parameters");
  ExpectRefused([](checkpoint_t& m) { m.initial.values[0] = 1e9; }, "initial.parameters.cols");
  ExpectRefused([](checkpoint_t& m) { m.sim_values[0] = 2.5; }, "sim_parameters.cols");
  ExpectRefused([nan](checkpoint_t& m) { m.scene.wind_velocity[1] = nan; }, "scene.wind_velocity[1]");
  ExpectRefused([](checkpoint_t& m) { m.scene.camera_width = 0; }, "scene.camera size");
  ExpectRefused([nan](checkpoint_t& m) { m.scene.camera_transform[5] = nan; }, "camera_transform[5]");
  ExpectRefused([](checkpoint_t& m) { m.scene.timeline.speed = 0; }, "scene.timeline.speed");
  ExpectRefused([](checkpoint_t& m) { m.scene.timeline.keys[0].law = 9; }, "scene.timeline.keys[0]");
  ExpectRefused([nan](checkpoint_t& m) { m.scene.glide_elapsed = nan; }, "glide_elapsed");
  ExpectRefused([](checkpoint_t& m) { m.substeps = 0; }, "substeps");
  // More than a session's checks let a flag need: a step of 65536 substeps times the guard's 16.
  ExpectRefused([](checkpoint_t& m) { m.substeps = sim::kMaxSubsteps + 1; },
                "substeps: 4097; allowed 1 .. 4096");
  ExpectRefused([](checkpoint_t& m) { m.guard_factor = 1000; }, "guard_factor");
  ExpectRefused([nan](checkpoint_t& m) { m.wind_carried = nan; }, "wind_carried");
  ExpectRefused([](checkpoint_t& m) { m.timeline_segment = -5; }, "timeline_segment");
  ExpectRefused([](checkpoint_t& m) { m.integrator_memory.num_nodes = 5; }, "integrator_memory.num_nodes");
  ExpectRefused([](checkpoint_t& m) { m.rollback_velocities = {}; }, "rollback_velocities.num_nodes");
  ExpectRefused([](checkpoint_t& m) { m.rollback_step = m.step + 1; }, "rollback_step");
  ExpectRefused([](checkpoint_t& m) { m.rollback_positions.z[2] = std::numeric_limits<float>::quiet_NaN(); },
                "rollback_positions: a value");
  ExpectRefused([](checkpoint_t& m) { m.calm_steps = -1; }, "calm_steps");
  ExpectRefused([](checkpoint_t& m) { m.calm_steps = 3; }, "calm_start.num_nodes");
}

/// `scene` stepped `steps` steps, once straight through and once rebuilt from its checkpoint,
/// read off the wire, every 7 steps: the same steps bit for bit. Returns the most calm steps any
/// of the checkpoints carried.
int ExpectTheSameRunThroughCheckpoints(const Scene& scene, int steps) {
  Session original(scene);
  auto resumed = std::make_unique<Session>(scene);
  int calm_steps = 0;
  for (int i = 1; i <= steps; ++i) {
    original.Step();
    resumed->Step();
    if (i % 7 != 0) continue;
    const checkpoint_t message = OverTheWire(MakeCheckpointMessage(resumed->Snapshot(), "periodic", 1));
    calm_steps = std::max(calm_steps, int(message.calm_steps));
    SessionSnapshot snapshot;
    EXPECT_EQ(ReadCheckpoint(message, &snapshot), "");
    resumed = std::make_unique<Session>(snapshot);
  }
  const std::string integrator = sim::IntegratorName(scene.sim.integrator);
  EXPECT_EQ(resumed->simulation().Hash(), original.simulation().Hash()) << integrator;
  EXPECT_EQ(resumed->simulation().sleeping(), original.simulation().sleeping()) << integrator;
  return calm_steps;
}

// What the integrator, the guard and the sleep watch carry from step to step crosses the wire:
// velocity Verlet's forces and implicit Euler's first guess under the busy timeline, and the
// watch of a flag settling in still air (which falls asleep on the way).
TEST(CheckpointCodec, WhatTheSimulationCarriesCrossesTheWire) {
  for (const sim::IntegratorKind kind :
       {sim::IntegratorKind::kVelocityVerlet, sim::IntegratorKind::kImplicitEuler}) {
    Scene busy = Busy();
    busy.sim.integrator = kind;
    ExpectTheSameRunThroughCheckpoints(busy, 200);
  }
  Scene still;
  still.sim.cols = 8;
  still.sim.rows = 6;
  still.sim.forces.friction = 5.0;
  still.wind = {{0, 0, 0}, 0, 0};
  EXPECT_GT(ExpectTheSameRunThroughCheckpoints(still, 3000), 0);
  Session asleep(still);
  for (int i = 0; i < 3000; ++i) asleep.Step();
  EXPECT_TRUE(asleep.simulation().sleeping());
}

}  // namespace
}  // namespace flagsim
