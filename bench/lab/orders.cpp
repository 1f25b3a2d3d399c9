// Convergence orders. A 16 x 12 breeze flag with linear springs in steady wind for 0.05 s (short enough that
// the motion is smooth and not yet chaotic), each integrator at five steps halving from its stability limit
// (explicit) or 1/60 s, errors against converged RK4; the order is the log-log slope between the two finest
// steps whose errors stay 10 times above the reference's own. The seed's scheme is left out: its friction law
// (-mu F) makes it a different ODE from the reference's.
#include <cmath>

#include "bench/lab/experiments.hpp"
#include "bench/lab/lab_setup.hpp"
#include "bench/lab/table.hpp"

namespace flagsim::lab {
namespace {

std::string Theory(sim::IntegratorKind kind) {
  switch (kind) {
    case sim::IntegratorKind::kVelocityVerlet:
      return "2";
    case sim::IntegratorKind::kRk4:
      return "4";
    default:
      return "1";
  }
}

}  // namespace

void Orders(const std::string& csv) {
  Trial base = PresetTrial("breeze", 0.05);
  base.params.cols = 16;
  base.params.rows = 12;
  base.wind.gust = 0;
  // Linear springs: with another stiffness in compression a spring's force has a kink at its
  // rest length, which caps every method near order 2 (RK4 measured 2.18 at compression = 0.3).
  // The orders are the methods' own, on a smooth problem.
  base.params.compression = 1;
  References references(base);
  const References::Converged converged = references.Converge(1e-9);
  const sim::ClothState<double>& reference = references.At(converged.substeps);
  Table table({"integrator", "h0_s", "e(h0)_m", "e(h0/2)_m", "e(h0/4)_m", "e(h0/8)_m", "e(h0/16)_m", "order",
               "theory"},
              csv);
  for (const sim::IntegratorKind kind : AllIntegrators()) {
    if (kind == sim::IntegratorKind::kSeed) continue;
    Trial trial = base;
    trial.params.integrator = kind;
    const std::vector<double> steps = StepSweep(trial, 5);
    std::vector<std::string> row = {sim::IntegratorName(kind), Table::Number(steps[0])};
    std::vector<double> errors;
    for (const double h : steps) {
      errors.push_back(RmsDistance(RunFixed<double>(trial, SubstepsFor(trial, h)), reference));
      row.push_back(Table::Number(errors.back()));
    }
    // The finest pair still well above the reference's own error.
    size_t fine = errors.size() - 1;
    while (fine > 1 && errors[fine] < 10 * converged.self_error) --fine;
    row.push_back(Table::Number(std::log2(errors[fine - 1] / errors[fine])));
    row.push_back(Theory(kind));
    table.Add(row);
  }
}

}  // namespace flagsim::lab
