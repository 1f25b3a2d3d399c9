// How flagctl prints what the server says, when what it says is damaged: a choice's default that
// is no index, a grid of no size. (The tables' layout is checked by integration.cli.)
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
