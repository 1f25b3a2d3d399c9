// Bullet's soft body on the lab's work-precision chart (bullet_bench --work-precision).
#pragma once

#include <string>

namespace flagsim {

/// The lab's work-precision flag (lab::LoadWorkPrecisionScene) run by BulletFlag at 2 ms steps
/// (and `steps` - 1 halvings of it) with `iterations` position iterations, scored against the lab's reference
/// and timed as the lab times flagsim; then, in the same run, every flagsim integrator at one step (2 ms if
/// it is unconditionally stable, else 0.9 of its limit), so that costs compare within one run; then how far
/// flagsim itself lands from the reference with the parts of Bullet's model it can copy. Rows as the lab's
/// work-precision CSV, written to `csv` unless it is empty.
void BulletWorkPrecision(int iterations, int steps, const std::string& csv);

}  // namespace flagsim
