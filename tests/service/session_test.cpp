// The session under a keyframe timeline: controls applied at step boundaries in simulated time,
// substeps per segment, edits during play, rejections that change nothing, and the same states
// at any thread count.
#include "server/service/session.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "server/scene/scene_timeline.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim {
namespace {

sim::Keyframe Key(double time, std::vector<sim::ParameterControl> parameters,
                  sim::ControlLaw law = sim::ControlLaw::kLinear) {
  sim::Keyframe key;
  key.time = time;
  key.law = law;
  key.parameters = std::move(parameters);
  return key;
}

/// A scene whose timeline stiffens the flag from 1000 to 3000 N/m over 4 s, playing.
Scene Stiffening() {
  Scene scene;
  scene.timeline.Add(Key(0, {{"stiffness", 1000}}));
  scene.timeline.Add(Key(4, {{"stiffness", 3000}}));
  scene.timeline.Play();
  return scene;
}

TimelineEdit Operation(TimelineEdit::Operation operation, double time = 0) {
  TimelineEdit edit;
  edit.operation = operation;
  edit.time = time;
  return edit;
}

// A scene that settles starts from the drape its own physics and wind give the flat flag after
// `settle` seconds, with the clock at 0; a reset goes back to that drape.
TEST(Session, ASettlingSceneStartsFromItsDrapeWithTheClockAtZero) {
  Scene scene;
  scene.settle = 0.5;
  Session session(scene);
  EXPECT_EQ(session.simulation().state().time, 0);
  EXPECT_EQ(session.simulation().state().step, 0);
  FlagSimulation by_hand(scene.sim, scene.wind, scene.seed);  // the same half second, stepped here
  while (by_hand.state().time < scene.settle) by_hand.Step();
  EXPECT_EQ(session.simulation().state().x, by_hand.state().x);
  EXPECT_EQ(session.simulation().state().vy, by_hand.state().vy);
  EXPECT_NE(session.simulation().state().x, sim::RestState(session.simulation().model()).x);
  for (int i = 0; i < 100; ++i) session.Step();
  ASSERT_EQ(session.ApplyParams({true, {}}), "");
  EXPECT_EQ(session.simulation().state().x, by_hand.state().x);
  EXPECT_EQ(session.simulation().state().step, 100) << "the clock goes on through a reset";
}

TEST(Session, APlayingTimelineDrivesTheControlsInSimulatedTime) {
  Session session(Stiffening());
  EXPECT_EQ(session.scene().sim.forces.stiffness, 1000);  // the timeline's start, from the first step
  EXPECT_EQ(session.simulation().params().forces.stiffness, 1000);
  const double dt = session.scene().sim.dt;
  for (int i = 0; i < 250; ++i) session.Step();
  // Step 249 started at 249 dt: 1000 + 500/s there.
  EXPECT_NEAR(session.scene().sim.forces.stiffness, 1000 + 500 * 249 * dt, 1e-9);
  EXPECT_EQ(session.simulation().params().forces.stiffness, session.scene().sim.forces.stiffness);
  EXPECT_NEAR(session.scene().timeline.position(), 250 * dt, 1e-12);
  EXPECT_EQ(session.scene().sim.cols, Scene{}.sim.cols);  // nothing else moved
}

TEST(Session, SpeedScalesTheTimelineNotTheSimulation) {
  Scene scene = Stiffening();
  scene.timeline.SetSpeed(2);
  Session session(scene);
  for (int i = 0; i < 100; ++i) session.Step();
  EXPECT_NEAR(session.scene().timeline.position(), 2 * 100 * scene.sim.dt, 1e-12);
  EXPECT_NEAR(session.simulation().state().time, 100 * scene.sim.dt, 1e-12);
}

TEST(Session, ThePausedTimelineLeavesTheControlsToCommands) {
  Session session(Stiffening());
  for (int i = 0; i < 10; ++i) session.Step();
  ASSERT_EQ(session.ApplyTimeline(Operation(TimelineEdit::kPause)), "");
  ParamChange change;
  change.assignments = {{"stiffness", "2500"}};
  ASSERT_EQ(session.ApplyParams(change), "");
  const double position = session.scene().timeline.position();
  for (int i = 0; i < 10; ++i) session.Step();
  EXPECT_EQ(session.scene().sim.forces.stiffness, 2500);
  EXPECT_EQ(session.scene().timeline.position(), position);
}

// Scrubbing a paused timeline previews it: the controls become what the keys set at the new
// position, at once, and stay there (the timeline does not move while paused).
TEST(Session, ASeekWhilePausedAppliesWhatTheKeysSetThere) {
  Session session(Stiffening());
  for (int i = 0; i < 10; ++i) session.Step();
  ASSERT_EQ(session.ApplyTimeline(Operation(TimelineEdit::kPause)), "");
  ASSERT_EQ(session.ApplyTimeline(Operation(TimelineEdit::kSeek, 3)), "");
  EXPECT_NEAR(session.scene().sim.forces.stiffness, 2500, 1e-9) << "1000 + 500/s at 3 s";
  EXPECT_EQ(session.simulation().params().forces.stiffness, session.scene().sim.forces.stiffness);
  for (int i = 0; i < 10; ++i) session.Step();
  EXPECT_NEAR(session.scene().sim.forces.stiffness, 2500, 1e-9);
  EXPECT_EQ(session.scene().timeline.position(), 3);
}

// Explicit steps: on entering a segment the substeps are fixed for its stiffest setting, so a
// flag stiffened tenfold never needs the guard.
TEST(Session, SubstepsAreFixedPerSegmentForItsStiffestSetting) {
  Scene scene;
  scene.wind.velocity = {12, 0, 3};
  scene.timeline.Add(Key(0, {{"stiffness", 2000}}));
  scene.timeline.Add(Key(0.5, {{"stiffness", 20000}}));
  scene.timeline.Add(Key(1, {{"stiffness", 2000}}));
  scene.timeline.Play();
  Session session(scene);
  sim::SimParams stiff = scene.sim;
  stiff.forces.stiffness = 20000;
  int first = 0;
  for (int i = 0; i < 500; ++i) {  // 0 to 1 s: both segments reach 20000 N/m
    session.Step();
    if (i == 0) first = session.simulation().substeps();
    EXPECT_GE(session.simulation().substeps(), sim::SubstepsFor(stiff)) << "step " << i;
    EXPECT_EQ(session.simulation().substeps(), first) << "step " << i;
  }
  for (int i = 0; i < 10; ++i) session.Step();  // from the last key on, 2000 N/m holds
  EXPECT_FALSE(session.scene().timeline.playing());
  EXPECT_EQ(session.scene().sim.forces.stiffness, 2000);
  EXPECT_EQ(session.simulation().substeps(), sim::SubstepsFor(scene.sim));
  EXPECT_LT(session.simulation().substeps(), first);
  EXPECT_EQ(session.simulation().recoveries(), 0);
}

// A key changed during play: the stiffness never jumps; the jump the edit would make dies away
// over the glide (smooth law: peak rate 1.5 times the mean) on top of the new curve's rate.
TEST(Session, KeysEditedDuringPlayMakeNoJump) {
  Session session(Stiffening());
  const double dt = session.scene().sim.dt;
  for (int i = 0; i < 1000; ++i) session.Step();  // 2 s in: 2000 N/m
  TimelineEdit edit;
  edit.operation = TimelineEdit::kAdd;
  edit.key = Key(4, {{"stiffness", 7000}});  // replaces the key at 4 s: the curve at 2 s is 4000
  ASSERT_EQ(session.ApplyTimeline(edit), "");
  double largest = 0, last = session.scene().sim.forces.stiffness;
  for (int i = 0; i < 500; ++i) {
    session.Step();
    largest = std::max(largest, std::abs(session.scene().sim.forces.stiffness - last));
    last = session.scene().sim.forces.stiffness;
  }
  EXPECT_LT(largest, (1500 + 2000 * 1.5 / sim::Timeline::kGlideTime) * dt * 1.01);
  EXPECT_NEAR(last, 1000 + 1500 * (session.scene().timeline.position() - dt), 1e-6);  // on the new curve

  // Removed: the key at 4 s gone, the first key's 1000 holds; the way down is glided too.
  ASSERT_EQ(session.ApplyTimeline(Operation(TimelineEdit::kRemove, 4)), "");
  largest = 0;
  for (int i = 0; i < 500; ++i) {
    session.Step();
    largest = std::max(largest, std::abs(session.scene().sim.forces.stiffness - last));
    last = session.scene().sim.forces.stiffness;
  }
  EXPECT_LT(largest, 1.5 * (5500 - 1000) / sim::Timeline::kGlideTime * dt * 1.01);  // from 5497 or so
  EXPECT_EQ(last, 1000);
}

TEST(Session, PlayGlidesFromTheValuesInForce) {
  Scene scene;
  scene.timeline.Add(Key(0, {{"stiffness", 5000}}));
  Session session(scene);
  for (int i = 0; i < 10; ++i) session.Step();
  EXPECT_EQ(session.scene().sim.forces.stiffness, scene.sim.forces.stiffness);  // not playing: the scene's
  ASSERT_EQ(session.ApplyTimeline(Operation(TimelineEdit::kPlay)), "");
  session.Step();
  EXPECT_EQ(session.scene().sim.forces.stiffness, scene.sim.forces.stiffness);  // where it was, then on
  session.Step();
  EXPECT_GT(session.scene().sim.forces.stiffness, scene.sim.forces.stiffness);
  for (int i = 0; i < 200; ++i) session.Step();
  EXPECT_EQ(session.scene().sim.forces.stiffness, 5000);
}

TEST(Session, ChangeMergesIntoTheKeyAndCanMoveIt) {
  Session session(Stiffening());
  TimelineEdit edit;
  edit.operation = TimelineEdit::kChange;
  edit.time = 4;
  edit.keep_law = true;
  edit.key = Key(5, {{"damping", 0.2}}, sim::ControlLaw::kStep);
  ASSERT_EQ(session.ApplyTimeline(edit), "");
  const sim::Timeline& timeline = session.scene().timeline;
  ASSERT_EQ(timeline.keys().size(), 2u);
  const sim::Keyframe& moved = timeline.keys()[1];
  EXPECT_EQ(moved.time, 5);
  EXPECT_EQ(moved.law, sim::ControlLaw::kLinear);  // kept
  EXPECT_EQ(*moved.Parameter("stiffness"), 3000);  // kept
  EXPECT_EQ(*moved.Parameter("damping"), 0.2);     // added
}

TEST(Session, RejectedTimelineEditsChangeNothing) {
  Session session(Stiffening());
  for (int i = 0; i < 20; ++i) session.Step();
  const sim::Timeline before = session.scene().timeline;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  TimelineEdit bad_key;
  bad_key.key = Key(1, {{"stiffness", nan}});
  TimelineEdit not_animatable;
  not_animatable.key = Key(1, {{"cols", 40}});
  TimelineEdit moved_onto_a_key = Operation(TimelineEdit::kChange, 4);
  moved_onto_a_key.key = Key(0, {{"gravity", 9}});
  TimelineEdit stopped = Operation(TimelineEdit::kSpeed);
  stopped.speed = 0;
  const std::vector<std::pair<TimelineEdit, std::string>> rejected = {
      {bad_key, "key.parameters.stiffness:"},
      {not_animatable, "key.parameters.cols:"},
      {Operation(TimelineEdit::kRemove, 3), "time: no key at 3 s; keys at 0, 4 s"},
      {Operation(TimelineEdit::kChange, 3), "time: no key at 3 s"},
      {moved_onto_a_key, "key.time: a key is at 0 s already"},
      {Operation(TimelineEdit::kSeek, nan), "time:"},
      {Operation(TimelineEdit::kSeek, -1), "time:"},
      {stopped, "speed: 0; allowed above 0"},
  };
  for (const auto& [edit, reason] : rejected) {
    EXPECT_EQ(session.ApplyTimeline(edit).rfind(reason, 0), 0u) << session.ApplyTimeline(edit);
    EXPECT_EQ(session.scene().timeline, before);
  }
  // One key too many, as a whole.
  Scene full;
  for (size_t i = 0; i < TimelineLimits::kMaxKeys; ++i) full.timeline.Add(Key(double(i), {{"gravity", 9}}));
  Session crowded(full);
  TimelineEdit one_more;
  one_more.key = Key(1000, {{"gravity", 8}});
  EXPECT_EQ(crowded.ApplyTimeline(one_more).rfind("keys: 257 of them; allowed at most 256", 0), 0u);
  EXPECT_EQ(crowded.scene().timeline, full.timeline);
}

// A PARAM change the keys could not live with is refused; a reset brings back the scene's timeline.
TEST(Session, ParametersMustSuitTheTimelineAndResetRestoresIt) {
  Scene scene;
  scene.timeline.Add(Key(0, {{"stiffness", 2000}}));
  scene.timeline.Add(Key(2, {{"stiffness", 100000}, {"damping", 0}}));
  Session session(scene);
  ParamChange explicit_euler;
  explicit_euler.assignments = {{"integrator", "explicit_euler"}};
  EXPECT_EQ(session.ApplyParams(explicit_euler).rfind("timeline: keys: at their stiffest", 0), 0u);
  EXPECT_EQ(session.scene().sim.integrator, scene.sim.integrator);

  ASSERT_EQ(session.ApplyTimeline(Operation(TimelineEdit::kClear)), "");
  ASSERT_NE(session.scene().timeline, scene.timeline);
  ParamChange reset;
  reset.reset_to_scene = true;
  ASSERT_EQ(session.ApplyParams(reset), "");
  EXPECT_EQ(session.scene().timeline, scene.timeline);
}

// Play needs a key to play: without one it is refused and the timeline stays paused.
TEST(Session, PlayWithoutKeysIsRefused) {
  Session session{Scene{}};
  EXPECT_EQ(session.ApplyTimeline(Operation(TimelineEdit::kPlay)),
            "operation: play with no keys; add one first (keyframe add)");
  EXPECT_FALSE(session.scene().timeline.playing());
  EXPECT_FALSE(session.scene().timeline.gliding());
}

// A reset restores the physics (parameters, wind, the flag at rest); the camera stays where the
// viewer put it.
TEST(Session, AResetKeepsTheCamera) {
  Session session{Scene{}};
  render::CameraMove orbit;
  orbit.operation = render::CameraMove::kOrbit;
  orbit.angle = 0.5;
  ASSERT_EQ(session.ApplyCamera(orbit), "");
  const render::Camera moved = session.scene().camera;
  ASSERT_NE(moved.eye, Scene{}.camera.eye);
  ParamChange change;
  change.assignments = {{"stiffness", "2500"}};
  ASSERT_EQ(session.ApplyParams(change), "");
  ParamChange reset;
  reset.reset_to_scene = true;
  ASSERT_EQ(session.ApplyParams(reset), "");
  EXPECT_EQ(session.scene().sim.forces.stiffness, Scene{}.sim.forces.stiffness);
  EXPECT_EQ(session.scene().camera.eye, moved.eye);
  EXPECT_EQ(session.scene().camera.target, moved.target);
}

/// A session whose timeline turns and strengthens the wind, stiffens the cloth and moves the
/// camera, on a loop, after `steps` steps at `threads` threads.
uint64_t HashAfter(int threads, int steps, bool with_timeline) {
  Scene scene;
  scene.sim.threads = threads;
  scene.sim.min_nodes_per_thread = 1;  // share even a small flag among the threads
  if (with_timeline) {
    sim::Keyframe first = Key(0, {{"stiffness", 1500}, {"damping", 0.05}}, sim::ControlLaw::kCubic);
    first.wind = sim::WindControl{{6, 0, 1.5}, 0.2};
    first.camera = sim::CameraControl{{2.6, 1.9, 4.4}, {0.8, 2.2, 0}, 40};
    scene.timeline.Add(first);
    sim::Keyframe turned = Key(0.4, {{"stiffness", 4000}}, sim::ControlLaw::kSmooth);
    turned.wind = sim::WindControl{{1, 0, -9}, 0.35};
    scene.timeline.Add(turned);
    sim::Keyframe last = first;
    last.time = 0.8;
    last.camera = sim::CameraControl{{4, 2, 2}, {0.8, 2.2, 0}, 50};
    scene.timeline.Add(last);
    scene.timeline.SetLoop(true);
    scene.timeline.Play();
  }
  Session session(scene);
  for (int i = 0; i < steps; ++i) {
    session.Step();
    if (i == steps / 2 && with_timeline) {  // and an edit during play
      TimelineEdit edit;
      edit.key = Key(0.6, {{"gravity", 7}});
      EXPECT_EQ(session.ApplyTimeline(edit), "");
    }
  }
  return session.simulation().Hash();
}

TEST(Session, APlayingTimelineGivesTheSameStatesAtAnyThreadCount) {
  const uint64_t one = HashAfter(1, 600, true);
  EXPECT_EQ(HashAfter(2, 600, true), one);
  EXPECT_NE(HashAfter(1, 600, false), one);  // and the timeline did something
}

}  // namespace
}  // namespace flagsim
