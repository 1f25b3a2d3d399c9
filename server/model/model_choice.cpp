#include "server/model/model_choice.hpp"

namespace flagsim::model {
namespace {

bool Fits(const Candidate& c, double cost_budget) { return c.cost <= cost_budget; }
bool Within(const Candidate& c, double budget_px) { return c.error_px <= budget_px; }

/// The index minimising key(candidate) among those `eligible` accepts; the first on ties; -1 if none.
template <typename Eligible, typename Key>
int Best(const std::vector<Candidate>& candidates, Eligible eligible, Key key) {
  int best = -1;
  for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
    if (!eligible(candidates[i])) continue;
    if (best < 0 || key(candidates[i]) < key(candidates[best])) best = i;
  }
  return best;
}

}  // namespace

Choice ChooseModel(const std::vector<Candidate>& candidates, double budget_px, double cost_budget, int current,
                   double hysteresis) {
  const auto cost = [](const Candidate& c) { return c.cost; };
  const auto error = [](const Candidate& c) { return c.error_px; };
  const bool has_current = current >= 0 && current < static_cast<int>(candidates.size());
  // 1. The cheapest within the budget that fits.
  const auto good = [&](const Candidate& c) { return Within(c, budget_px) && Fits(c, cost_budget); };
  if (const int best = Best(candidates, good, cost); best >= 0) {
    const bool keep = has_current && good(candidates[current]) &&
                      candidates[current].cost <= (1 + hysteresis) * candidates[best].cost;
    return {keep ? current : best, ChoiceKind::kWithinBudget};
  }
  // 2. The most accurate that fits.
  const auto fits = [&](const Candidate& c) { return Fits(c, cost_budget); };
  if (const int best = Best(candidates, fits, error); best >= 0) {
    const bool keep = has_current && fits(candidates[current]) &&
                      candidates[current].error_px <= (1 + hysteresis) * candidates[best].error_px;
    return {keep ? current : best, ChoiceKind::kMostAccurateInRealTime};
  }
  // 3. The cheapest.
  const int best = Best(candidates, [](const Candidate&) { return true; }, cost);
  const bool keep = has_current && candidates[current].cost <= (1 + hysteresis) * candidates[best].cost;
  return {keep ? current : best, ChoiceKind::kCheapestNotInRealTime};
}

std::string Describe(ChoiceKind kind) {
  switch (kind) {
    case ChoiceKind::kWithinBudget:
      return "within the budget";
    case ChoiceKind::kMostAccurateInRealTime:
      return "the most accurate in real time (the budget is out of reach)";
    case ChoiceKind::kCheapestNotInRealTime:
      return "the cheapest, not in real time (nothing fits)";
  }
  return "";
}

}  // namespace flagsim::model
