// Cost per node-substep of every integrator, 32 x 24 to 512 x 384 nodes, on one thread: the
// server's Simulation<float> on the breeze preset with its automatic substeps, timed in CPU
// seconds of the stepping thread over enough steps to fill a quarter second. Memory: bytes the
// allocator holds once the simulation is built and has stepped, per node.
#include <malloc.h>

#include <algorithm>

#include "bench/lab/experiments.hpp"
#include "bench/lab/lab_setup.hpp"
#include "bench/lab/table.hpp"
#include "lab/cpu_time.hpp"
#include "server/scene/scene_file.hpp"
#include "server/sim/simulation.hpp"

namespace flagsim::lab {
namespace {

/// Bytes in use from the allocator (small blocks and mapped ones).
double BytesInUse() {
  const struct mallinfo2 info = mallinfo2();
  return double(info.uordblks) + double(info.hblkhd);
}

constexpr double kMeasureSeconds = 0.25;

}  // namespace

void Cost(const std::string& csv) {
  const Scene scene = LoadScene("breeze");
  Table table({"integrator", "cols", "rows", "nodes", "substeps", "ms_per_step", "ns_per_node_substep",
               "bytes_per_node"},
              csv);
  for (const sim::IntegratorKind kind : AllIntegrators()) {
    for (const int scale : {1, 2, 4, 8, 16}) {
      sim::SimParams params = scene.sim;
      params.cols = 32 * scale;
      params.rows = 24 * scale;
      params.integrator = kind;
      const double before = BytesInUse();
      sim::Simulation<float> simulation(params, scene.wind, scene.seed);
      simulation.Step();
      const double bytes = BytesInUse() - before;
      const double per_step = CpuSecondsPerCall(kMeasureSeconds, [&] { simulation.Step(); });
      const double nodes = double(params.cols) * params.rows;
      table.Add({sim::IntegratorName(kind), std::to_string(params.cols), std::to_string(params.rows),
                 Table::Number(nodes), std::to_string(simulation.substeps()), Table::Number(1e3 * per_step),
                 Table::Number(1e9 * per_step / (nodes * simulation.substeps())),
                 Table::Number(bytes / nodes)});
    }
  }
}

}  // namespace flagsim::lab
