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
  // the forward-difference step of the Jacobian: false, 1e-6 max(1, |z|) in the fitted space
  // (a smooth, table-driven forward model); true, the step of coarse_difference_step (a
  // forward model that is a time-stepped simulation: its output moves with a parameter only
  // in steps of the integrator's switches, the friction's stick/slip branches and elements
  // entering contact, so below some size a difference measures those switches, not the
  // parameter's effect; the kinematics rig's AP moves by 0.5 um RMS per 1e-6 of friction,
  // 16 times the slope between friction 0.02 and 0.07)
  bool coarse_jacobian = false;
  // above 1: independent fits (multi-starts, held-out folds, candidates) run side by side, for
  // a forward model that limits its own parallel simulations (DiagnosisCase::prefetch), and the
  // detection-limit replicates on this many threads; every result is the same as in sequence
  int threads = 1;
};

// a difference step inside the bounds in the fitted space, large against a simulation's
// switching noise: 0.05 in log space, 2 % of the range otherwise (towards the inside at the
// upper bound); the detection limits' linearisation uses the same step
double coarse_difference_step(const ParamSpec& s, double value);

// runs the forward model at several parameter vectors [I/O units] ahead of the sequential
// evaluations that follow (a forward model that caches and runs simulations in parallel);
// must not change any result, only when it is computed
using PrefetchFn = std::function<void(const std::vector<Eigen::VectorXd>& params)>;

// minimises |r(params)|^2 from `initial`, plus every combination of the specs' extra starts
// when `multi_start`
FitResult fit_least_squares(const ResidualsFn& residuals, const std::vector<ParamSpec>& specs,
                            const Eigen::VectorXd& initial, bool multi_start,
                            const FitControl& control = {}, const PrefetchFn& prefetch = {});

}  // namespace kneesim::diagnosis
