// The automatic model's choice: among candidate models of the flag (integrator, substeps, grid),
// each with its estimated screen_error (px, frame_defect.hpp plus resolution_error.hpp) and its
// cost (CPU seconds per simulated second, from the cost model, not from the clock: the choice must
// not depend on how busy the machine is), take
//   1. the cheapest whose error is within the budget and whose cost fits the cost budget;
//   2. if none is within the budget at a cost that fits, the most accurate that fits, and say so;
//   3. if none fits at all, the cheapest, and say so.
// Hysteresis keeps the model in force while it stays a good answer: it is kept if it is an answer
// of the same kind (1, 2 or 3) and within `hysteresis` of the best (cost for 1 and 3, error for 2),
// so that estimates that wobble from one evaluation to the next do not flip the model back and
// forth. Ties go to the earlier candidate: the same inputs give the same choice on any machine.
#pragma once

#include <string>
#include <vector>

#include "server/sim/sim_params.hpp"

namespace flagsim::model {

struct Candidate {
  sim::IntegratorKind integrator = sim::IntegratorKind::kSymplecticEuler;
  int substeps = 1;            ///< per step
  int cols = 32, rows = 24;    ///< the grid
  double error_px = 0;         ///< estimated screen_error
  double cost = 0;             ///< CPU seconds per simulated second
};

/// Which of the three kinds of answer a choice is (the top of this file).
enum class ChoiceKind { kWithinBudget, kMostAccurateInRealTime, kCheapestNotInRealTime };

struct Choice {
  int index = -1;  ///< into the candidates; -1 only for an empty list
  ChoiceKind kind = ChoiceKind::kWithinBudget;
};

/// The choice among `candidates` for `budget_px` and `cost_budget`, keeping `current` (an index,
/// or -1 for none) by the hysteresis rule (a fraction, 0.1 for 10%).
Choice ChooseModel(const std::vector<Candidate>& candidates, double budget_px, double cost_budget, int current,
                   double hysteresis);

/// "within the budget", "the most accurate in real time", "cheapest, not in real time".
std::string Describe(ChoiceKind kind);

}  // namespace flagsim::model
