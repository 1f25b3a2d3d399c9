// What a fluttering flag looks like, as numbers that a grid-independent cloth keeps at every grid
// (a chaotic flag's trajectories part within a fraction of a second; its statistics do not):
//   reach, height  the fly edge's mean position: horizontal distance from the pole's axis, and y
//   spread         the RMS distance of the fly edge's mean position from its time average
//   curvature      the mean over interior nodes of |L x|, the discrete mean curvature normal's
//                  length (bending.hpp): 1/m, 1/R on a cylinder of radius R at any grid
//   fold spacing   the wavelength of the folds along the rows and down the columns: twice the
//                  length of grid lines over the sign changes of the normal curvature (L x) . n
//                  along them, a change counted only across a band of +-1/4 of the sample's mean
//                  curvature (a Schmitt trigger), so that noise about zero does not count
//   flutter        the frequency of the fly edge's motion across the wind: half its crossings of
//                  its mean (again with a band of 1/4 of its spread) per second
// Each comes with a 95% confidence interval from batch means: the samples cut into consecutive
// batches whose means are taken as independent (true when a batch is much longer than the
// motion's correlation time; the flutter's period is about 1 s, batches are 2 s or more).
#pragma once

#include <string>
#include <vector>

#include "server/sim/cloth_model.hpp"
#include "server/sim/cloth_state.hpp"

namespace flagsim::lab {

/// One frame of the flag, reduced.
struct ShapeSample {
  double t = 0;                ///< s
  double fly[3] = {0, 0, 0};   ///< m: the fly edge's mean position
  double curvature = 0;        ///< 1/m: mean |L x| over interior nodes
  double folds_along = 0;      ///< sign changes of the normal curvature along the rows, summed
  double folds_down = 0;       ///< and down the columns
  double length_along = 0;     ///< m of interior grid line those were counted over, along the rows
  double length_down = 0;      ///< and down the columns
};

template <typename Real>
ShapeSample SampleShape(const sim::ClothModel<Real>& model, const sim::ClothState<Real>& state);

/// A statistic: its mean and the half-width of its 95% confidence interval.
struct Estimate {
  double mean = 0;
  double half_width = 0;
};

struct ShapeStatistics {
  Estimate reach, height, spread, curvature, fold_along, fold_down, flutter;
  int batches = 0;
};

/// Of samples taken at equal intervals, cut into `batches` batches.
ShapeStatistics SummariseShape(const std::vector<ShapeSample>& samples, int batches);

/// The batch means' mean and 95% half-width (Student's t with batches - 1 degrees of freedom).
Estimate BatchEstimate(const std::vector<double>& batch_means);

/// Crossings of `values` through `centre` that pass the whole band centre +- band.
int SchmittCrossings(const std::vector<double>& values, double centre, double band);

}  // namespace flagsim::lab
