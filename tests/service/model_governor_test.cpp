#include "server/service/model_governor.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <string>

#include "flagsim/applied_command_t.hpp"
#include "messages/checked_decode.hpp"
#include "messages/event_log_reader.hpp"
#include "server/scene/parameter_table.hpp"
#include "server/service/message_builders.hpp"
#include "server/service/replay.hpp"
#include "server/service/server.hpp"
#include "tests/service/log_fixtures.hpp"
#include "tests/service/simulated_clock.hpp"

namespace flagsim {
namespace {

Scene Set(Scene scene, const std::string& name, const std::string& value) {
  EXPECT_EQ(ParameterTable::Get().Assign(name, value, &scene), "");
  return scene;
}

int64_t Steps(double seconds, const Scene& scene) { return std::llround(std::ceil(seconds / scene.sim.dt)); }

// The flat flag at the start has no curvature to resolve: auto asks at step 0 and coarsens it,
// exactly kLatency later, whatever the machine's speed.
TEST(ModelGovernor, ADecisionTakesEffectAFixedLatencyAfterItsQuestion) {
  Session session{Scene{}};
  ModelGovernor governor;
  const int64_t due = Steps(ModelGovernor::kLatency, session.scene());
  for (int64_t step = 0; step < due; ++step) {
    EXPECT_FALSE(governor.AtBoundary(session).has_value()) << "at step " << step;
    session.Step();
  }
  const std::optional<model::ModelDecision> decision = governor.AtBoundary(session);
  ASSERT_TRUE(decision.has_value());
  EXPECT_LT(decision->cols * decision->rows, 32 * 24) << model::Describe(*decision);
  EXPECT_LE(decision->error_px, Scene{}.model.error_budget);
  ASSERT_TRUE(governor.last().has_value());
  EXPECT_EQ(session.ApplyModel({decision->integrator, decision->solver_iterations, decision->cols, decision->rows}),
            "");
  EXPECT_EQ(session.scene().sim.cols, decision->cols);
  EXPECT_EQ(session.simulation().model().cols, decision->cols);
  EXPECT_EQ(session.simulation().state().step, due);  // the switch takes no step
}

// integrator=rk4 is the user's: auto may change the grid only, and says what it would choose.
TEST(ModelGovernor, AnIntegratorSetByTheUserIsHonoured) {
  Session session{Set(Scene{}, "integrator", "rk4")};
  EXPECT_FALSE(session.scene().model.auto_integrator);
  EXPECT_TRUE(session.scene().model.auto_grid);
  ModelGovernor governor;
  const int64_t due = Steps(ModelGovernor::kLatency, session.scene());
  for (int64_t step = 0; step <= due; ++step) {
    if (const auto decision = governor.AtBoundary(session)) {
      EXPECT_EQ(decision->integrator, sim::IntegratorKind::kRk4) << model::Describe(*decision);
    }
    session.Step();
  }
  ASSERT_TRUE(governor.last().has_value());
  EXPECT_EQ(governor.last()->chosen.integrator, sim::IntegratorKind::kRk4);
  status_t status{};
  status.real_time_factor = 1;
  WriteModelStatus(session, governor.last(), &status);
  EXPECT_EQ(status.model_auto, "grid");
  EXPECT_NE(status.model_note.find("set by the user: the integrator; auto would choose "), std::string::npos)
      << status.model_note;
  EXPECT_GE(status.screen_error_px, 0);
}

TEST(ModelGovernor, ADecisionIsRefusedWhereTheUserSetTheWholeModel) {
  Session session{Set(Set(Scene{}, "integrator", "verlet"), "cols", "20")};
  const uint64_t before = session.simulation().Hash();
  EXPECT_NE(session.ApplyModel({sim::IntegratorKind::kXpbd, 2, 16, 12}).find("auto chooses neither"),
            std::string::npos);
  EXPECT_EQ(session.simulation().Hash(), before);
  EXPECT_EQ(session.scene().sim.integrator, sim::IntegratorKind::kVelocityVerlet);
}

TEST(ModelGovernor, ADecisionOutOfRangeChangesNothing) {
  Session session{Scene{}};
  const uint64_t before = session.simulation().Hash();
  EXPECT_EQ(session.ApplyModel({sim::IntegratorKind::kXpbd, 2, 1, 12}).rfind("cols: 1 is out of range", 0), 0u);
  EXPECT_EQ(session.ApplyModel({sim::IntegratorKind::kXpbd, 0, 16, 12}).rfind("solver_iterations:", 0), 0u);
  EXPECT_EQ(session.ApplyModel({sim::IntegratorKind(99), 2, 16, 12}).rfind("integrator:", 0), 0u);
  EXPECT_EQ(session.simulation().Hash(), before);
  EXPECT_EQ(session.scene().sim.cols, 32);
}

/// MODEL entries in the APPLIED journal of the log at `path`.
int ModelSwitchesIn(const std::string& path, const Channels& channels) {
  EventLogReader reader(path);
  LogEvent event;
  int switches = 0;
  while (reader.Next(&event, [&](const std::string& channel) { return channel == channels.applied; })) {
    std::string error;
    const auto message = wire::CheckedDecode<applied_command_t>(event.data.data(), event.data.size(), 1 << 20, &error);
    if (message && message->channel == "MODEL") ++switches;
  }
  return switches;
}

// The breeze under auto, on a simulated clock: auto switches grids as the folds grow, each switch
// is journaled, and the record replays bit for bit across them, at one thread and at two.
TEST(ModelGovernor, SwitchesAreJournaledAndReplayBitForBit) {
  const std::string path = testing::TempPath("auto.lcmlog");
  const Channels channels;
  Bus bus("memq://");
  testing::SimulatedClock clock;
  ServerOptions options = clock.ServerOnIt();
  options.duration = 6;
  options.inputs_log = path;
  Scene scene;
  scene.service.frame_rate = 10;
  Server server(bus, channels, scene, options);
  clock.StepUntil(server, [&] { return server.session().simulation().state().time >= options.duration; });
  const std::atomic<bool> stop{false};
  server.Run(stop);
  const int switches = ModelSwitchesIn(path, channels);
  EXPECT_GE(switches, 2);  // coarser for the flat start, finer as it folds
  for (const int threads : {1, 2}) {
    ReplayOptions replay;
    replay.threads = threads;
    const ReplayReport report = Replay(path, replay);
    EXPECT_TRUE(report.ok()) << report.error << report.divergence;
    EXPECT_EQ(report.model_switches, switches);
    EXPECT_EQ(report.commands, 0);
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace flagsim
