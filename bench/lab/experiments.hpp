// The physics lab's experiments. Each prints a table and, given a path, writes it as CSV; the
// charts in docs/ are drawn from those files (bench/charts/lab.sh).
#pragma once

#include <string>

namespace flagsim::lab {

/// Convergence orders: log-log slopes of error against step for each integrator.
void Orders(const std::string& csv);
/// Work against precision: error (m and px) against CPU cost per simulated second, every
/// integrator over a sweep of steps (and iterations for xpbd and projective).
void WorkPrecision(const std::string& csv);
/// Stability map: the largest stable step against structural stiffness, with the theory.
void StabilityMap(const std::string& csv);
/// Cost per node-substep of every integrator from 32 x 24 to 512 x 384 nodes, one thread, and
/// the memory each adds per node.
void Cost(const std::string& csv);
/// Thread sweep: wall time per step at 1 and 2 threads, speedup and efficiency.
void Threads(const std::string& csv);
/// For each preset scene, the cheapest integrator and step whose error stays under a pixel.
void Cheapest(const std::string& csv);

}  // namespace flagsim::lab
