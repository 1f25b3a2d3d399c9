#include "server/model/model_choice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace flagsim::model {
namespace {

/// n candidates with errors and costs spread over four decades, from a fixed seed.
std::vector<Candidate> RandomCandidates(std::mt19937* random, int n) {
  std::uniform_real_distribution<double> decades(-2, 2);
  std::vector<Candidate> candidates(n);
  for (Candidate& c : candidates) {
    c.error_px = std::pow(10.0, decades(*random));
    c.cost = std::pow(10.0, decades(*random));
  }
  return candidates;
}

// The rule the issue states, checked on the model rather than timed: the choice never exceeds the
// budget when a candidate within it fits the cost budget; within the budget it is the cheapest, or
// the model in force within the hysteresis of the cheapest; otherwise the most accurate that fits,
// or the cheapest when nothing fits.
TEST(ModelChoice, NeverExceedsTheBudgetWhenACandidateWithinItFits) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 20000; ++trial) {
    const std::vector<Candidate> candidates = RandomCandidates(&random, 1 + trial % 12);
    const double budget = 1.0, cost_budget = std::pow(10.0, std::uniform_real_distribution<double>(-1, 1)(random));
    const int current = int(random() % (candidates.size() + 1)) - 1;
    const Choice choice = ChooseModel(candidates, budget, cost_budget, current, 0.1);
    ASSERT_GE(choice.index, 0);
    const Candidate& chosen = candidates[choice.index];
    double cheapest_good = INFINITY, best_error_fitting = INFINITY, cheapest = INFINITY;
    for (const Candidate& c : candidates) {
      if (c.cost <= cost_budget && c.error_px <= budget) cheapest_good = std::min(cheapest_good, c.cost);
      if (c.cost <= cost_budget) best_error_fitting = std::min(best_error_fitting, c.error_px);
      cheapest = std::min(cheapest, c.cost);
    }
    if (std::isfinite(cheapest_good)) {
      EXPECT_EQ(choice.kind, ChoiceKind::kWithinBudget);
      EXPECT_LE(chosen.error_px, budget);
      EXPECT_LE(chosen.cost, cost_budget);
      EXPECT_LE(chosen.cost, (choice.index == current ? 1.1 : 1.0) * cheapest_good);
    } else if (std::isfinite(best_error_fitting)) {
      EXPECT_EQ(choice.kind, ChoiceKind::kMostAccurateInRealTime);
      EXPECT_LE(chosen.cost, cost_budget);
      EXPECT_LE(chosen.error_px, (choice.index == current ? 1.1 : 1.0) * best_error_fitting);
    } else {
      EXPECT_EQ(choice.kind, ChoiceKind::kCheapestNotInRealTime);
      EXPECT_LE(chosen.cost, (choice.index == current ? 1.1 : 1.0) * cheapest);
    }
  }
}

TEST(ModelChoice, KeepsTheModelInForceWithinTheHysteresisAndLeavesItBeyond) {
  std::vector<Candidate> candidates(2);
  candidates[0].error_px = 0.5;
  candidates[0].cost = 0.50;
  candidates[1].error_px = 0.8;
  candidates[1].cost = 0.53;  // 6% dearer than the cheapest: kept while in force
  EXPECT_EQ(ChooseModel(candidates, 1.0, 1.0, 1, 0.1).index, 1);
  EXPECT_EQ(ChooseModel(candidates, 1.0, 1.0, -1, 0.1).index, 0);
  candidates[1].cost = 0.60;  // 20% dearer: left
  EXPECT_EQ(ChooseModel(candidates, 1.0, 1.0, 1, 0.1).index, 0);
  candidates[1].error_px = 1.2;  // over the budget: left whatever it costs
  candidates[1].cost = 0.1;
  EXPECT_EQ(ChooseModel(candidates, 1.0, 1.0, 1, 0.1).index, 0);
}

TEST(ModelChoice, SaysWhenTheBudgetIsOutOfReachInRealTime) {
  std::vector<Candidate> candidates(3);
  candidates[0] = {sim::IntegratorKind::kSymplecticEuler, 65, 128, 96, 0.06, 6.4};  // accurate, too dear
  candidates[1] = {sim::IntegratorKind::kXpbd, 1, 128, 96, 2.1, 0.9};
  candidates[2] = {sim::IntegratorKind::kImplicitEuler, 1, 128, 96, 0.44, 0.95};
  const Choice choice = ChooseModel(candidates, 0.2, 1.0, -1, 0.1);
  EXPECT_EQ(choice.index, 2);
  EXPECT_EQ(choice.kind, ChoiceKind::kMostAccurateInRealTime);
  EXPECT_EQ(ChooseModel(candidates, 0.2, 0.5, -1, 0.1).kind, ChoiceKind::kCheapestNotInRealTime);
  EXPECT_EQ(ChooseModel(candidates, 0.2, 0.5, -1, 0.1).index, 1);
  EXPECT_TRUE(ChooseModel({}, 1, 1, -1, 0.1).index < 0);
}

}  // namespace
}  // namespace flagsim::model
