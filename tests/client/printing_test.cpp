// How flagctl prints what the server says, when what it says is damaged or hostile: a choice's
// default that is no index, control characters, a grid of no size. (The tables' layout is
// checked by integration.cli.)
#include "client/printing.hpp"

#include <gtest/gtest.h>

#include <climits>
#include <sstream>

namespace flagsim {
namespace {

TEST(PrintParams, AChoiceDefaultThatIsNoIndexPrintsAsANumber) {
  params_t params{};
  parameter_t row{};
  row.name = "shading";
  row.kind = parameter_t::CHOICE;
  row.choices = {"wireframe", "flat"};
  row.num_choices = 2;
  row.default_value = 5.7e250;
  params.parameters = {row};
  params.num_parameters = 1;
  std::ostringstream out;
  PrintParams(params, out);
  EXPECT_NE(out.str().find("5.7e+250"), std::string::npos) << out.str();
  params.parameters[0].default_value = 1;
  out.str("");
  PrintParams(params, out);
  EXPECT_NE(out.str().find("flat"), std::string::npos) << out.str();
}

// What the bus says is printed with its control characters escaped: a server (or anyone on the
// bus) cannot clear the terminal, retitle it or move its cursor through flagctl.
TEST(PrintParams, ControlCharactersFromTheBusAreEscaped) {
  params_t params{};
  parameter_t row{};
  row.name = "stiff\x1b[2Jness";
  row.value_text = "1\r\n";
  row.unit = "N/m\x07";
  row.description = "\x1b]0;owned\x07 \xc2\x9b 2J, \xc3\xbc kept";
  params.parameters = {row};
  params.num_parameters = 1;
  std::ostringstream out;
  PrintParams(params, out);
  EXPECT_EQ(out.str().find('\x1b'), std::string::npos) << out.str();
  EXPECT_EQ(out.str().find('\x07'), std::string::npos) << out.str();
  EXPECT_EQ(out.str().find('\r'), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("stiff\\x1b[2Jness"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("\\x1b]0;owned\\x07 \\xc2\\x9b 2J, \xc3\xbc kept"), std::string::npos)
      << out.str();
}

TEST(PrintStatus, ControlCharactersFromTheBusAreEscaped) {
  status_t status{};
  status.integrator = "xpbd\x1b[1A";
  status.last_recovery = "at step 3\x1b[2K";
  status.command_authentication = "none\x1b[31m";
  status.model_note = "auto\x1b[0m";
  std::ostringstream out;
  PrintStatus(status, out);
  EXPECT_EQ(out.str().find('\x1b'), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("xpbd\\x1b[1A"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("at step 3\\x1b[2K"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("none\\x1b[31m"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("auto\\x1b[0m"), std::string::npos) << out.str();
}

TEST(PrintStatus, TheModelInForceAndAutosWord) {
  status_t status{};
  status.cols = 48;
  status.rows = 36;
  status.integrator = "xpbd";
  status.substeps = 1;
  status.model_auto = "integrator and grid";
  status.screen_error_px = 0.62;
  status.model_cost = 0.21;
  status.model_note = "auto: within the budget of 1 px";
  std::ostringstream out;
  PrintStatus(status, out);
  EXPECT_NE(out.str().find("model:             48 x 36, xpbd, 1 substeps; auto chooses integrator and grid"),
            std::string::npos)
      << out.str();
  EXPECT_NE(out.str().find("screen_error:      0.62 px estimated, 0.21 of real time"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("auto:              auto: within the budget of 1 px"), std::string::npos) << out.str();
}

TEST(PrintTimeline, ControlCharactersFromTheBusAreEscaped) {
  timeline_t timeline{};
  timeline_key_t key{};
  key.names = {"stiffness\x1b[2J"};
  key.values = {1500};
  key.num_parameters = 1;
  timeline.keys = {key};
  timeline.num_keys = 1;
  std::ostringstream out;
  PrintTimeline(timeline, out);
  EXPECT_EQ(out.str().find('\x1b'), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("stiffness\\x1b[2J=1500"), std::string::npos) << out.str();
}

TEST(TipText, AGridOfNoSizeHasNoTip) {
  state_t state{};
  state.cols = INT_MIN;
  state.position = {1, 2, 3};
  state.num_values = 3;
  EXPECT_EQ(TipText(state), "(none)");
  state.cols = 1;
  EXPECT_EQ(TipText(state), "(1.000, 2.000, 3.000)");
}

}  // namespace
}  // namespace flagsim
