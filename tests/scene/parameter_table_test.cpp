#include "server/scene/parameter_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>

namespace flagsim {
namespace {

const ParameterTable& Table() { return ParameterTable::Get(); }

/// Every parameter's value in `scene`, to check that a rejection changed nothing.
std::vector<double> Values(const Scene& scene) {
  std::vector<double> values;
  for (const Parameter& parameter : Table().parameters()) values.push_back(parameter.get(scene));
  return values;
}

std::vector<std::string> BadTexts(const Parameter& parameter) {
  switch (parameter.kind) {
    case ParameterKind::kBoolean:
      return {"maybe", "", "2", "nan"};
    case ParameterKind::kChoice:
      return {"nope", "", "0", "nan", parameter.choices[0] + " "};
    case ParameterKind::kInteger:
    case ParameterKind::kReal:
      break;
  }
  const double span = parameter.max_value - parameter.min_value;
  std::vector<std::string> texts = {"nan",
                                    "NaN",
                                    "inf",
                                    "-inf",
                                    "infinity",
                                    "",
                                    "1x",
                                    "abc",
                                    parameter.Format(parameter.min_value - std::max(1.0, span)),
                                    parameter.Format(parameter.max_value + std::max(1.0, span))};
  if (parameter.kind == ParameterKind::kInteger)
    texts.push_back(parameter.Format(parameter.min_value) + ".5");
  return texts;
}

TEST(ParameterTable, HasTheParametersTheDesignPromises) {
  for (const char* name : {"mass", "stiffness", "shear_stiffness", "bending_stiffness", "damping", "friction",
                           "wind_coefficient", "gravity", "dt", "integrator", "cols", "rows", "threads"}) {
    EXPECT_NE(Table().Find(name), nullptr) << name;
  }
}

TEST(ParameterTable, EveryBadValueIsRejectedWithItsNameAndRangeAndChangesNothing) {
  for (const Parameter& parameter : Table().parameters()) {
    for (const std::string& text : BadTexts(parameter)) {
      Scene scene;
      const std::vector<double> before = Values(scene);
      const std::string reason = Table().Assign(parameter.name, text, &scene);
      EXPECT_FALSE(reason.empty()) << parameter.name << "=" << text << " was accepted";
      EXPECT_EQ(reason.rfind(parameter.name + ":", 0), 0u) << reason;
      EXPECT_NE(reason.find(parameter.AllowedText()), std::string::npos) << reason;
      EXPECT_EQ(Values(scene), before) << parameter.name << "=" << text;
    }
  }
}

TEST(ParameterTable, UnknownNamesAreRejectedWithTheKnownOnes) {
  Scene scene;
  const std::string reason = Table().Assign("stifness", "100", &scene);
  EXPECT_NE(reason.find("unknown parameter 'stifness'"), std::string::npos);
  EXPECT_NE(reason.find("stiffness"), std::string::npos);
}

// What a PARAM sends is echoed in its answer as printable text of bounded length: a 64 KiB
// name or value with escape sequences takes a line of the reason, not 64 KiB of control bytes.
TEST(ParameterTable, ANameOrValueIsEchoedPrintableAndCut) {
  const std::string hostile = "\x1b[2J" + std::string(64 * 1024, 'x');
  Scene scene;
  for (const std::string& reason :
       {Table().Assign("stiffness", hostile, &scene), Table().Assign("cols", hostile, &scene),
        Table().Assign("relative_wind", hostile, &scene), Table().Assign("shading", hostile, &scene),
        Table().Assign(hostile, "1", &scene)}) {
    EXPECT_LT(reason.size(), 1000u) << reason.substr(0, 200);
    EXPECT_EQ(reason.find('\x1b'), std::string::npos) << reason.substr(0, 200);
    EXPECT_NE(reason.find("'\\x1b[2Jxxx"), std::string::npos) << reason.substr(0, 200);
    EXPECT_NE(reason.find("xxx...'"), std::string::npos) << reason.substr(0, 200);
  }
  const std::string out_of_range = "1" + std::string(200, '0');  // 1e200: a number, of 201 digits
  const std::string reason = Table().Assign("stiffness", out_of_range, &scene);
  EXPECT_EQ(reason.rfind("stiffness: 100000000", 0), 0u) << reason;
  EXPECT_NE(reason.find("... is out of range; allowed 1 .. 1e+05 N/m"), std::string::npos) << reason;
  EXPECT_EQ(Values(scene), Values(Scene{}));
}

TEST(ParameterTable, DefaultsAndLimitsAreAccepted) {
  for (const Parameter& parameter : Table().parameters()) {
    for (const double value : {parameter.default_value(), parameter.min_value, parameter.max_value}) {
      Scene scene;
      EXPECT_EQ(Table().Assign(parameter.name, parameter.Format(value), &scene), "") << parameter.name;
      EXPECT_EQ(parameter.get(scene), value) << parameter.name;
    }
    EXPECT_GE(parameter.default_value(), parameter.min_value) << parameter.name;
    EXPECT_LE(parameter.default_value(), parameter.max_value) << parameter.name;
  }
}

TEST(ParameterTable, AssignmentsReachTheScene) {
  Scene scene;
  EXPECT_EQ(Table().Assign("stiffness", "1234.5", &scene), "");
  EXPECT_EQ(Table().Assign("cols", "40", &scene), "");
  EXPECT_EQ(Table().Assign("relative_wind", "on", &scene), "");
  EXPECT_EQ(Table().Assign("integrator", "seed", &scene), "");
  EXPECT_EQ(Table().Assign("state_rate", "30", &scene), "");
  EXPECT_EQ(scene.sim.forces.stiffness, 1234.5);
  EXPECT_EQ(scene.sim.cols, 40);
  EXPECT_TRUE(scene.sim.relative_wind);
  EXPECT_EQ(scene.sim.integrator, sim::IntegratorKind::kSeed);
  EXPECT_EQ(scene.service.state_rate, 30);
}

TEST(ParameterTable, SeedFrictionMustBeAFraction) {
  Scene scene;
  scene.sim.integrator = sim::IntegratorKind::kSeed;
  scene.sim.forces.friction = 1.5;
  EXPECT_NE(ParameterTable::CheckConsistency(scene).find("friction"), std::string::npos);
  scene.sim.forces.friction = 0.5;
  EXPECT_EQ(ParameterTable::CheckConsistency(scene), "");
}

TEST(ParameterTable, WindChecksNameTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ParameterTable::CheckWind(sim::WindSettings{{5, 0, 1}, 0.2, 3}), "");
  EXPECT_EQ(ParameterTable::CheckWind(sim::WindSettings{{nan, 0, 0}, 0, 0}).rfind("velocity.x:", 0), 0u);
  EXPECT_EQ(ParameterTable::CheckWind(sim::WindSettings{{0, 0, -inf}, 0, 0}).rfind("velocity.z:", 0), 0u);
  EXPECT_EQ(ParameterTable::CheckWind(sim::WindSettings{{50, 50, 0}, 0, 0}).rfind("velocity:", 0), 0u);
  EXPECT_EQ(ParameterTable::CheckWind(sim::WindSettings{{1, 0, 0}, nan, 0}).rfind("gust:", 0), 0u);
  EXPECT_EQ(ParameterTable::CheckWind(sim::WindSettings{{1, 0, 0}, 1.5, 0}).rfind("gust:", 0), 0u);
  EXPECT_EQ(ParameterTable::CheckWind(sim::WindSettings{{1, 0, 0}, 0, -1}).rfind("ramp_time:", 0), 0u);
  EXPECT_EQ(ParameterTable::CheckWind(sim::WindSettings{{1, 0, 0}, 0, inf}).rfind("ramp_time:", 0), 0u);
}

}  // namespace
}  // namespace flagsim

namespace flagsim {
namespace {

// auto is the default; a value fixes the setting and keeps the other; auto gives it back, and the
// value goes on holding the setting in force.
TEST(ParameterTable, AutoIsASwitchBesideTheSettingInForce) {
  const ParameterTable& table = ParameterTable::Get();
  Scene scene;
  EXPECT_TRUE(scene.model.auto_integrator);
  EXPECT_TRUE(scene.model.auto_grid);
  ASSERT_EQ(table.Assign("integrator", "rk4", &scene), "");
  EXPECT_FALSE(scene.model.auto_integrator);
  EXPECT_TRUE(scene.model.auto_grid);
  ASSERT_EQ(table.Assign("cols", "64", &scene), "");
  EXPECT_FALSE(scene.model.auto_grid);
  EXPECT_EQ(scene.sim.rows, 24);  // the other size stays as it stands
  ASSERT_EQ(table.Assign("rows", "auto", &scene), "");
  EXPECT_TRUE(scene.model.auto_grid);
  EXPECT_EQ(scene.sim.cols, 64);
  ASSERT_EQ(table.Assign("integrator", "auto", &scene), "");
  EXPECT_TRUE(scene.model.auto_integrator);
  EXPECT_EQ(scene.sim.integrator, sim::IntegratorKind::kRk4);
  EXPECT_EQ(table.Find("integrator")->AllowedText().find(", auto"), table.Find("integrator")->AllowedText().size() - 6);
  EXPECT_NE(table.Assign("cols", "automatic", &scene).find("allowed 2 .. 512, or auto"), std::string::npos);
  EXPECT_NE(table.Assign("threads", "auto", &scene).find("'auto' is not an integer"), std::string::npos);
}

// With integrator=auto, settings no explicit integrator can step in time get xpbd at once; set
// by the user, the explicit one is refused with the reason.
TEST(ParameterTable, AutoSettlesOnAStableIntegratorWhereAnExplicitOneCannotKeepUp) {
  Scene scene;  // 128 x 96, stiff, in long steps: symplectic Euler would need 7616 substeps a step
  for (const auto& [name, value] : {std::pair{"cols", "128"}, {"rows", "96"}, {"stiffness", "100000"},
                                    {"bending_stiffness", "1"}, {"dt", "0.05"}}) {
    ASSERT_EQ(ParameterTable::Get().Assign(name, value, &scene), "");
  }
  Scene set_by_user = scene;
  ASSERT_EQ(ParameterTable::Get().Assign("integrator", "symplectic_euler", &set_by_user), "");
  EXPECT_NE(ParameterTable::CheckConsistency(set_by_user).find("substeps"), std::string::npos);
  ParameterTable::SettleAutoModel(&scene);
  EXPECT_EQ(scene.sim.integrator, sim::IntegratorKind::kXpbd);
  EXPECT_EQ(ParameterTable::CheckConsistency(scene), "");
}

}  // namespace
}  // namespace flagsim
