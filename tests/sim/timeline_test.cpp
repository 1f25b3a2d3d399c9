#include "server/sim/timeline.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flagsim::sim {
namespace {

Keyframe Stiffness(double time, double value, ControlLaw law = ControlLaw::kLinear) {
  Keyframe key;
  key.time = time;
  key.law = law;
  key.parameters = {{"stiffness", value}};
  return key;
}

Keyframe Wind(double time, Vec3 velocity, ControlLaw law = ControlLaw::kLinear, double gust = 0) {
  Keyframe key;
  key.time = time;
  key.law = law;
  key.wind = WindControl{velocity, gust};
  return key;
}

double ParameterAt(const Timeline& timeline, double position, const std::string& name = "stiffness") {
  for (const ParameterControl& parameter : timeline.Evaluate(position).parameters) {
    if (parameter.name == name) return parameter.value;
  }
  ADD_FAILURE() << name << " is not set at " << position;
  return NAN;
}

double Speed(const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/// The wind's heading in the horizontal plane, rad: 0 along +x, pi/2 along -z.
double Heading(const Vec3& v) { return std::atan2(-v[2], v[0]); }

// Keys at 0, 2 and 4 s with stiffness 1000, 3000, 2000, every key with the same law.
Timeline ThreeKeys(ControlLaw law) {
  Timeline timeline;
  timeline.Add(Stiffness(0, 1000, law));
  timeline.Add(Stiffness(2, 3000, law));
  timeline.Add(Stiffness(4, 2000, law));
  return timeline;
}

TEST(Timeline, EveryLawIsExactAtItsKeys) {
  for (const ControlLaw law :
       {ControlLaw::kStep, ControlLaw::kLinear, ControlLaw::kSmooth, ControlLaw::kCubic}) {
    const Timeline timeline = ThreeKeys(law);
    EXPECT_EQ(ParameterAt(timeline, 0), 1000) << ControlLawNames()[int(law)];
    EXPECT_EQ(ParameterAt(timeline, 2), 3000) << ControlLawNames()[int(law)];
    EXPECT_EQ(ParameterAt(timeline, 4), 2000) << ControlLawNames()[int(law)];
  }
}

TEST(Timeline, EachLawBetweenKeys) {
  // Halfway through (0, 2): step holds 1000; linear 2000; smooth at a quarter, s = 1/4:
  // 3/16 - 2/64 = 0.15625 of the way.
  EXPECT_EQ(ParameterAt(ThreeKeys(ControlLaw::kStep), 1.999), 1000);
  EXPECT_DOUBLE_EQ(ParameterAt(ThreeKeys(ControlLaw::kLinear), 1), 2000);
  EXPECT_DOUBLE_EQ(ParameterAt(ThreeKeys(ControlLaw::kSmooth), 0.5), 1000 + 2000 * 0.15625);
  // Cubic on (0, 2): no key before, so the rate at 0 is the secant's, (3000 - 1000) / 2; at 2
  // Catmull-Rom's, (2000 - 1000) / (4 - 0). Times the span 2: m0 = 2000, m1 = 500. At s = 1/2
  // the Hermite value is (v0 + v1) / 2 + (m0 - m1) / 8.
  EXPECT_NEAR(ParameterAt(ThreeKeys(ControlLaw::kCubic), 1), 2000 + (2000 - 500) / 8.0, 1e-9);
  // Past the last key and before the first, the ends hold.
  EXPECT_EQ(ParameterAt(ThreeKeys(ControlLaw::kCubic), 9), 2000);
  Timeline late;
  late.Add(Stiffness(3, 1500));
  EXPECT_EQ(ParameterAt(late, 0), 1500);
}

TEST(Timeline, AControlNotSetByAKeyIsNotInterrupted) {
  // Stiffness at 0 and 4, wind at 0 and 2: the wind's key at 2 does not stop the stiffness.
  Timeline timeline;
  Keyframe first = Stiffness(0, 1000);
  first.wind = WindControl{{5, 0, 0}, 0.1};
  timeline.Add(first);
  timeline.Add(Wind(2, {7, 0, 0}));
  timeline.Add(Stiffness(4, 3000));
  EXPECT_DOUBLE_EQ(ParameterAt(timeline, 2), 2000);
  EXPECT_DOUBLE_EQ(ParameterAt(timeline, 3), 2500);
  const Controls at_one = timeline.Evaluate(1);
  ASSERT_TRUE(at_one.wind);
  EXPECT_DOUBLE_EQ(at_one.wind->velocity[0], 6);
  EXPECT_DOUBLE_EQ(at_one.wind->gust, 0.05);
  EXPECT_FALSE(at_one.camera);  // no key sets it: left alone
}

TEST(Timeline, WindTurnsByAngleWhileItsSpeedFollowsTheLaw) {
  // From 4 m/s along +x to 8 m/s along -z, linear over 2 s: halfway it blows 6 m/s at 45
  // degrees; componentwise it would blow (2, 0, -4), 4.5 m/s at 63 degrees.
  Timeline timeline;
  timeline.Add(Wind(0, {4, 0, 0}));
  timeline.Add(Wind(2, {0, 0, -8}));
  const Vec3 half = timeline.Evaluate(1).wind->velocity;
  EXPECT_NEAR(Speed(half), 6, 1e-12);
  EXPECT_NEAR(Heading(half), M_PI / 4, 1e-12);
  EXPECT_NEAR(half[1], 0, 1e-12);
  // A quarter of the time, a quarter of the turn.
  EXPECT_NEAR(Heading(timeline.Evaluate(0.5).wind->velocity), M_PI / 8, 1e-12);
}

TEST(Timeline, CubicWindKeepsTurningThroughAKeyAndSlowsToSwingBack) {
  const auto rate_either_side = [](const Timeline& timeline, double t) {
    const double h = 1e-4;
    const auto heading = [&](double at) { return Heading(timeline.Evaluate(at).wind->velocity); };
    return std::make_pair((heading(t) - heading(t - h)) / h, (heading(t + h) - heading(t)) / h);
  };
  // East, north, west a second apart: the turn goes on at 90 degrees per second through north.
  Timeline on;
  on.Add(Wind(0, {6, 0, 0}, ControlLaw::kCubic));
  on.Add(Wind(1, {0, 0, -6}, ControlLaw::kCubic));
  on.Add(Wind(2, {-6, 0, 0}, ControlLaw::kCubic));
  const auto [in, out] = rate_either_side(on, 1);
  EXPECT_NEAR(in, M_PI / 2, 1e-3);
  EXPECT_NEAR(out, M_PI / 2, 1e-3);
  // East, north, east: the wind comes to a stop at north before it swings back.
  Timeline back;
  back.Add(Wind(0, {6, 0, 0}, ControlLaw::kCubic));
  back.Add(Wind(1, {0, 0, -6}, ControlLaw::kCubic));
  back.Add(Wind(2, {6, 0, 0}, ControlLaw::kCubic));
  const auto [slowing, returning] = rate_either_side(back, 1);
  EXPECT_NEAR(slowing, 0, 1e-3);
  EXPECT_NEAR(returning, 0, 1e-3);
}

TEST(Timeline, CameraMovesByTheLaw) {
  Timeline timeline;
  Keyframe key;
  key.camera = CameraControl{{0, 2, 4}, {1, 2, 0}, 30};
  timeline.Add(key);
  key.time = 2;
  key.camera = CameraControl{{4, 2, 0}, {1, 3, 0}, 50};
  timeline.Add(key);
  const CameraControl camera = *timeline.Evaluate(0.5).camera;
  EXPECT_DOUBLE_EQ(camera.eye[0], 1);
  EXPECT_DOUBLE_EQ(camera.eye[2], 3);
  EXPECT_DOUBLE_EQ(camera.target[1], 2.25);
  EXPECT_DOUBLE_EQ(camera.fov, 35);
}

TEST(Timeline, AddingAtTheSameTimeReplacesAndKeysStayInOrder) {
  Timeline timeline;
  EXPECT_FALSE(timeline.Add(Stiffness(3, 1)));
  EXPECT_FALSE(timeline.Add(Stiffness(1, 2)));
  EXPECT_FALSE(timeline.Add(Stiffness(2, 3)));
  EXPECT_TRUE(timeline.Add(Stiffness(1, 4)));
  ASSERT_EQ(timeline.keys().size(), 3u);
  EXPECT_EQ(timeline.keys()[0].time, 1);
  EXPECT_EQ(*timeline.keys()[0].Parameter("stiffness"), 4);
  EXPECT_EQ(timeline.keys()[2].time, 3);
  EXPECT_EQ(timeline.End(), 3);
  EXPECT_TRUE(timeline.Remove(2));
  EXPECT_FALSE(timeline.Remove(2));
  EXPECT_EQ(timeline.SegmentAt(0.5), 0);
  EXPECT_EQ(timeline.SegmentAt(1), 1);
  EXPECT_EQ(timeline.SegmentAt(7), 2);
}

TEST(Timeline, AdvancesBySpeedTimesSimulatedTime) {
  Timeline timeline = ThreeKeys(ControlLaw::kLinear);
  timeline.Advance(0.5);
  EXPECT_EQ(timeline.position(), 0);  // paused
  timeline.Play();
  timeline.SetSpeed(2);
  timeline.Advance(0.25);
  EXPECT_EQ(timeline.position(), 0.5);
  timeline.Seek(3);
  timeline.SetSpeed(0.5);
  timeline.Advance(1);
  EXPECT_EQ(timeline.position(), 3.5);
}

TEST(Timeline, StopsAfterTheStepFromItsLastKeyUnlessItLoops) {
  Timeline timeline = ThreeKeys(ControlLaw::kLinear);
  timeline.Play();
  timeline.Seek(3.5);
  timeline.Advance(1);
  EXPECT_EQ(timeline.position(), 4);  // at the end, still to take the step from there
  EXPECT_TRUE(timeline.playing());
  timeline.Advance(1);
  EXPECT_FALSE(timeline.playing());
  EXPECT_EQ(timeline.position(), 4);

  timeline.SetLoop(true);
  timeline.Play();
  timeline.Seek(3.5);
  timeline.Advance(1.25);  // 4.75 wraps to 0.75
  EXPECT_DOUBLE_EQ(timeline.position(), 0.75);
  EXPECT_TRUE(timeline.playing());
  timeline.SetSpeed(10);
  timeline.Advance(1);  // 10.75 wraps twice, to 2.75
  EXPECT_DOUBLE_EQ(timeline.position(), 2.75);
}

TEST(Timeline, WithoutKeysNothingMoves) {
  Timeline timeline = ThreeKeys(ControlLaw::kLinear);
  timeline.Play();
  timeline.Seek(3);
  timeline.Clear();
  EXPECT_EQ(timeline.position(), 0);
  timeline.Advance(1);
  EXPECT_EQ(timeline.position(), 0);
  EXPECT_TRUE(timeline.playing());
  EXPECT_EQ(timeline.Evaluate(0), Controls{});
}

// Removing keys never leaves the position past the end: it moves to the new last key, and with
// no key left back to 0.
TEST(Timeline, RemovingTheLastKeysKeepsThePositionOnTheTimeline) {
  Timeline timeline = ThreeKeys(ControlLaw::kLinear);
  timeline.Seek(3.5);
  ASSERT_TRUE(timeline.Remove(4));
  EXPECT_EQ(timeline.position(), 2);
  ASSERT_TRUE(timeline.Remove(0));
  EXPECT_EQ(timeline.position(), 2);
  ASSERT_TRUE(timeline.Remove(2));
  EXPECT_EQ(timeline.position(), 0);
  EXPECT_EQ(timeline.End(), 0);
}

// Plays `steps` steps of dt and returns the largest change of stiffness from one to the next.
double LargestStepChange(Timeline* timeline, double dt, int steps) {
  double largest = 0, last = ParameterAt(*timeline, timeline->position());
  for (int i = 0; i < steps; ++i) {
    timeline->Advance(dt);
    const double now = ParameterAt(*timeline, timeline->position());
    largest = std::max(largest, std::abs(now - last));
    last = now;
  }
  return largest;
}

TEST(Timeline, KeysEditedDuringPlayGlideInsteadOfJumping) {
  // Linear from 1000 at 0 s to 3000 at 4 s: 500 per second, 1 per 2 ms step.
  const double dt = 0.002;
  Timeline timeline;
  timeline.Add(Stiffness(0, 1000));
  timeline.Add(Stiffness(4, 3000));
  timeline.Play();
  timeline.Seek(2);
  ASSERT_DOUBLE_EQ(ParameterAt(timeline, 2), 2000);

  // A key in a later segment leaves the values of this one as they were, bit for bit.
  Timeline later = timeline;
  later.Add(Stiffness(6, 9000));
  for (double t = 2; t < 4; t += 0.1) EXPECT_EQ(ParameterAt(later, t), ParameterAt(timeline, t));

  // The key at 4 s changed to 7000: the curve at 2 s is now 4000. With the glide the value
  // starts where it was, and the jump of -2000 dies away over kGlideTime by the smooth law, whose
  // peak rate is 1.5 times its mean: at most 1500/s (the curve's) + 2000 * 1.5 / kGlideTime.
  Timeline edited = timeline;
  edited.Add(Stiffness(4, 7000));
  EXPECT_DOUBLE_EQ(ParameterAt(edited, 2), 4000);
  edited.StartGlide(timeline.Evaluate(2));
  EXPECT_DOUBLE_EQ(ParameterAt(edited, 2), 2000);
  const double bound = (1500 + 2000 * 1.5 / Timeline::kGlideTime) * dt;
  EXPECT_LT(LargestStepChange(&edited, dt, 500), bound * 1.01);
  EXPECT_FALSE(edited.gliding());
  EXPECT_DOUBLE_EQ(ParameterAt(edited, edited.position()), 1000 + 1500 * edited.position());

  // Removed during play: the key at 4 s gone, 1000 holds from 0 s on; the glide takes it there.
  Timeline removed = timeline;
  removed.Remove(4);
  removed.StartGlide(timeline.Evaluate(2));
  EXPECT_DOUBLE_EQ(ParameterAt(removed, 2), 2000);
  EXPECT_LT(LargestStepChange(&removed, dt, 500), 1.5 * 1000 / Timeline::kGlideTime * dt * 1.01);
  EXPECT_EQ(ParameterAt(removed, removed.position()), 1000);
}

// An edit that leaves the values at the position as they were (a key in a later segment, for
// the linear law) starts a glide with nothing to smooth: the values are the timeline's, bit for bit.
TEST(Timeline, AGlideWithoutAJumpChangesNothing) {
  Timeline timeline;
  timeline.Add(Stiffness(0, 1000));
  timeline.Add(Stiffness(4, 3000));
  timeline.Add(Wind(0, {5, 0, 1}));
  timeline.Play();
  timeline.Seek(1);
  Timeline edited = timeline;
  edited.Add(Stiffness(6, 9000));
  edited.StartGlide(timeline.Evaluate(1));
  Timeline plain = timeline;
  plain.Add(Stiffness(6, 9000));
  for (int i = 0; i < 200; ++i) {
    EXPECT_EQ(edited.Evaluate(edited.position()), plain.Evaluate(plain.position()));
    edited.Advance(0.002);
    plain.Advance(0.002);
  }
}

// A glide of the wind turns it and changes its speed; it does not blow it through zero.
TEST(Timeline, AWindGlideTurnsTheWind) {
  Timeline timeline;
  timeline.Add(Wind(0, {0, 0, -6}));
  timeline.Play();
  Controls from;
  from.wind = WindControl{{3, 0, 0}, 0};
  timeline.StartGlide(from);
  const Vec3 first = timeline.Evaluate(0).wind->velocity;
  EXPECT_NEAR(first[0], 3, 1e-12);
  EXPECT_NEAR(first[2], 0, 1e-12);
  double last_heading = 0;
  for (int i = 1; timeline.gliding(); ++i) {
    timeline.Advance(0.002);
    const Vec3 wind = timeline.Evaluate(0).wind->velocity;
    const double w = timeline.gliding() ? 3 * std::pow(i * 0.002 / Timeline::kGlideTime, 2) -
                                              2 * std::pow(i * 0.002 / Timeline::kGlideTime, 3)
                                        : 1.0;
    EXPECT_NEAR(Speed(wind), 3 + 3 * w, 1e-9);  // the speed goes 3 -> 6 by the smooth law
    EXPECT_GE(Heading(wind), last_heading);     // and the heading turns one way, 0 -> 90 degrees
    last_heading = Heading(wind);
  }
  EXPECT_NEAR(last_heading, M_PI / 2, 1e-12);
}

TEST(Timeline, AGlideAtTheEndRunsItsCourseBeforePlayStops) {
  Timeline timeline;
  timeline.Add(Stiffness(0, 1000));
  timeline.Add(Stiffness(1, 3000));
  timeline.Play();
  timeline.Seek(1);
  Controls from;
  from.parameters = {{"stiffness", 2000}};
  timeline.StartGlide(from);
  const double dt = 1.0 / 64;  // exact in binary: the glide ends after kGlideTime / dt steps
  int steps = 0;
  while (timeline.playing() && steps < 1000) {
    ++steps;
    timeline.Advance(dt);
  }
  EXPECT_EQ(steps, int(Timeline::kGlideTime / dt) + 1);
  EXPECT_EQ(ParameterAt(timeline, timeline.position()), 3000);
}

TEST(Timeline, RangesHoldEveryValueTheSegmentReaches) {
  // Cubic keys 1000, 1000, 3000, 3000 two seconds apart: Catmull-Rom's rates at the middle keys
  // make the first segment dip below 1000 and the last rise above 3000.
  Timeline timeline;
  for (const auto& [time, value] : {std::pair{0.0, 1000.0}, {2.0, 1000.0}, {4.0, 3000.0}, {6.0, 3000.0}})
    timeline.Add(Stiffness(time, value, ControlLaw::kCubic));
  for (const double start : {0.0, 2.0, 4.0}) {
    const std::vector<ParameterRange> ranges = timeline.ParameterRanges(start + 0.5);
    ASSERT_EQ(ranges.size(), 1u);
    double low = INFINITY, high = -INFINITY;
    for (double t = start; t <= start + 2; t += 0.001) {
      low = std::min(low, ParameterAt(timeline, t));
      high = std::max(high, ParameterAt(timeline, t));
    }
    EXPECT_LE(ranges[0].low, low) << start;
    EXPECT_GE(ranges[0].high, high) << start;
    if (start == 0.0) {
      EXPECT_LT(low, 1000);  // the overshoots the ranges have to hold
    } else if (start == 4.0) {
      EXPECT_GT(high, 3000);
    }
  }
  // A glide under way widens the range by the jump still to die away: from 1000 (the timeline at
  // its position, 0 s) to 9000 in force.
  const double plain = timeline.ParameterRanges(4.5)[0].high;
  Controls from;
  from.parameters = {{"stiffness", 9000}};
  timeline.StartGlide(from);
  EXPECT_EQ(timeline.ParameterRanges(0.5)[0].high, 9000);
  EXPECT_EQ(timeline.ParameterRanges(4.5)[0].high, plain + 8000);
}

TEST(Timeline, ACopyIsACheckpoint) {
  Timeline timeline = ThreeKeys(ControlLaw::kCubic);
  timeline.Add(Wind(1, {3, 0, 1}));
  timeline.Play();
  timeline.SetLoop(true);
  for (int i = 0; i < 700; ++i) timeline.Advance(0.002);
  Timeline copy = timeline;
  EXPECT_EQ(copy, timeline);
  for (int i = 0; i < 5000; ++i) {
    timeline.Advance(0.002);
    copy.Advance(0.002);
  }
  EXPECT_EQ(copy, timeline);
  EXPECT_EQ(copy.Evaluate(copy.position()), timeline.Evaluate(timeline.position()));
  copy.Pause();
  EXPECT_NE(copy, timeline);
}

}  // namespace
}  // namespace flagsim::sim
