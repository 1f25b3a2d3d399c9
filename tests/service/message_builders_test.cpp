#include "message_builders.hpp"

#include <gtest/gtest.h>

#include "checked_decode.hpp"
#include "messages/message_fixtures.hpp"
#include "parameter_table.hpp"

namespace flagsim {
namespace {

TEST(MessageBuilders, StateCarriesEveryNodeAndTheHash) {
  Session session{Scene{}};
  for (int i = 0; i < 20; ++i) session.Step();
  const state_t state = MakeStateMessage(session, 123);
  const auto& sim = session.simulation();
  EXPECT_EQ(state.step, 20);
  EXPECT_EQ(state.cols * state.rows, sim.model().num_nodes());
  ASSERT_EQ(state.num_values, 3 * sim.model().num_nodes());
  EXPECT_EQ(static_cast<uint64_t>(state.state_hash), sim.Hash());
  const int last = sim.model().num_nodes() - 1;
  EXPECT_EQ(state.position[3 * last + 2], sim.state().z[last]);
  // and it survives the wire
  const auto bytes = testing::Encode(state);
  std::string error;
  const auto decoded = wire::CheckedDecode<state_t>(bytes.data(), bytes.size(), 1 << 20, &error);
  ASSERT_TRUE(decoded) << error;
  EXPECT_EQ(decoded->position, state.position);
}

TEST(MessageBuilders, ParamsListTheWholeTableWithCurrentValues) {
  Scene scene;
  scene.sim.stiffness = 777;
  const params_t params = MakeParamsMessage(scene, 1);
  ASSERT_EQ(params.num_params, static_cast<int32_t>(ParameterTable::Get().parameters().size()));
  bool found = false;
  for (const parameter_t& row : params.params) {
    if (row.name != "stiffness") continue;
    found = true;
    EXPECT_EQ(row.value, 777);
    EXPECT_EQ(row.value_text, "777");
    EXPECT_EQ(row.unit, "N/m");
    EXPECT_EQ(row.default_value, Scene{}.sim.stiffness);
  }
  EXPECT_TRUE(found);
  const auto bytes = testing::Encode(params);
  std::string error;
  EXPECT_TRUE(wire::CheckedDecode<params_t>(bytes.data(), bytes.size(), 1 << 20, &error)) << error;
}

TEST(MessageBuilders, StatusRatesAreOverTheWindow) {
  Session session{Scene{}};
  ServerStats stats;
  stats.steps = 250;
  stats.step_seconds = 0.05;
  stats.states_published = 30;
  stats.commands_rejected = 4;
  StatusWindow window;
  window.wall_seconds = 0.5;
  window.sim_seconds = 0.25;
  window.bytes = 1000;
  const status_t status = MakeStatusMessage(session, stats, window, 1);
  EXPECT_DOUBLE_EQ(status.steps_per_second, 500);
  EXPECT_DOUBLE_EQ(status.step_time_us, 200);
  EXPECT_DOUBLE_EQ(status.state_rate_hz, 60);
  EXPECT_DOUBLE_EQ(status.real_time_factor, 0.5);
  EXPECT_DOUBLE_EQ(status.bytes_per_second, 2000);
  EXPECT_EQ(status.commands_rejected, 4);
  EXPECT_EQ(status.integrator, "symplectic_euler");
}

}  // namespace
}  // namespace flagsim
