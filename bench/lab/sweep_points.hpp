// An experiment as independent points, so that a sweep runs on whatever engine is at hand (the
// machine's cores, a Slurm job array, a Kubernetes Indexed Job: scripts/sweep) and gathers into
// the same CSV the serial experiment writes.
//
//   lab points EXPERIMENT --out DIR     DIR/points.txt: a header, then one point a line
//   lab point --points FILE --index N   runs points N*chunk .. N*chunk + chunk - 1, each into
//                                       DIR/records/I.csv, written whole or not at all
//   lab gather --points FILE            DIR/EXPERIMENT.csv from the records, in the points'
//                                       order; names the points without a record
//
// A point is `key=value` words. Its record holds the experiment's columns, its one row, and a
// comment naming the node it ran on (host and CPU model): cost figures from different kinds of
// node are not to be compared. Experiments as points:
//   work-precision  one integrator (and its iterations) at one step; the reference's substeps
//                   are found once, when the points are written, and each task runs that
//                   reference once for its points
//   render          a scene rendered as flagd render does, its frames as PNG files in
//                   DIR/renders/I/ and their SHA-256 in the record
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bench/lab/work_precision_scene.hpp"

namespace flagsim::lab {

using Point = std::map<std::string, std::string>;

struct PointsOptions {
  bool quick = false;               ///< work-precision: two integrators, three steps each
  std::vector<std::string> scenes;  ///< render: presets or scene files
  double duration = 1;              ///< render: s of simulated time
  double fps = 10;                  ///< render: frames per simulated second
};

/// The work-precision chart's points on `scene` (work_precision.cpp runs them in turn): each
/// integrator and its iterations at each step of its sweep; `quick`, two integrators at three.
std::vector<Point> WorkPrecisionPoints(const WorkPrecisionScene& scene, bool quick);
/// A work-precision point's row; `*scene` is loaded (again) only for another reference.
std::vector<std::string> WorkPrecisionPointRow(const Point& point, std::optional<WorkPrecisionScene>* scene);

/// Writes DIR/points.txt for `experiment` (work-precision or render); returns the points' count.
int WritePoints(const std::string& experiment, const PointsOptions& options, const std::string& directory);

/// Runs points index * chunk .. (index + 1) * chunk - 1 of the points file (those that exist);
/// 0, or 1 if any failed (each failure said on stderr, its record not written).
int RunPoints(const std::string& points_file, int index, int chunk);

/// Gathers the records beside the points file into EXPERIMENT.csv there; 0 if every point has
/// one, else 1 after naming those missing (as indices of points and of tasks of `chunk`).
int GatherRecords(const std::string& points_file, int chunk);

}  // namespace flagsim::lab
