// Weighted nonlinear least squares for the diagnosis fits: Levenberg-Marquardt on a handful of
// parameters with a forward-difference Jacobian, in a transformed space (log for positive,
// multiplicative parameters; clamped to the bounds), with multi-start from the specs' starts.
// Small and dependency-free on purpose: the fits have at most four parameters and the forward
// model is a cheap table-driven simulation, so robustness (multi-start) matters more than speed.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "analysis/diagnosis/effect.h"

namespace kneesim::diagnosis {

// weighted residuals r(params) for params in I/O units
using ResidualsFn = std::function<Eigen::VectorXd(const Eigen::VectorXd& params)>;

struct FitResult {
  Eigen::VectorXd params;  // best parameters [I/O units]
  double rss = 0.0;        // sum of squared weighted residuals
  int evaluations = 0;     // residual evaluations [-]
};

// iteration control: a forward model that is a full simulation caps the work per fit
struct FitControl {
  int max_iterations = 100;  // Levenberg-Marquardt iterations per start [-]
  double tolerance = 1e-10;  // stop when a step lowers the cost by less than this fraction [-]
  // profile the specimen variance ratio with a refit of the parameters at every trial value
  // (exact profile likelihood); off for a forward model that is a full simulation, where the
  // noise parameters are profiled at the fitted parameters and the two alternate instead
  bool refit_in_noise_profile = true;
  // alternations between the fit and the error model's profile (each refits the parameters)
  int noise_iterations = 6;
};

// minimises |r(params)|^2 from `initial`, plus every combination of the specs' extra starts
// when `multi_start`
FitResult fit_least_squares(const ResidualsFn& residuals, const std::vector<ParamSpec>& specs,
                            const Eigen::VectorXd& initial, bool multi_start,
                            const FitControl& control = {});

}  // namespace kneesim::diagnosis
