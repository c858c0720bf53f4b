// Detection limits of a diagnosis (internal to the framework; reported through
// DiagnosisResult::detection): for every candidate and every parameter that sets its size
// (ParamSpec::null_value), the smallest departure from the null value that the selection rule
// names in `detection_rate` (80 %) of data sets simulated with the FITTED error model of the
// data: the refitted baseline's predictions, plus the effect at that size (its other parameters
// at their null or initial values), plus noise drawn from the profiled covariance (correlation,
// specimen random effects) and the nuisance terms' priors, of the model the data support (the
// named one, or the refitted baseline), plus the data's fitted nuisance contribution (a
// registration offset, a cell's drift), plus, where the case supplies them, one realization
// of the forward model's own error (DiagnosisCase::forward_error_draws: for forces, a direct
// simulation between grid values against the interpolated grid). Each replicate is diagnosed among `none` and every
// candidate with the gates and the selection rule of the real data (AICc drop, held-out drop
// against none and the trivial predictor, no parameter at a search bound; the lowest AICc,
// then the tie band's held-out RMSE), at the data's fitted noise state: the effect counts as
// named only when the selection picks it, not another candidate. The replicate's threshold
// size is found by bisection on ln(size) with common random numbers, and the limit is the
// required quantile of those thresholds. So a
// result `none` reads "no effect larger than the limit": below it, the data could not have
// told the effect from their noise.
//
// Where every evaluation is a full simulation (DiagnosisCase::expensive_forward: kinematics),
// the replicates use a local linear model of each candidate about its null point (one
// simulation per parameter, forward differences in the fitted space); the limit is then that
// of the linearized effect, accurate while the effect at the limit is small.
//
// The limit's size is also given as the RMS of the effect's identifiable signal (the part the
// baseline and the free nuisance terms cannot absorb, identifiable_signal) and as its ratio to
// the fitted noise RMS, the measure the hidden-effect tests use.
#pragma once

#include <Eigen/Core>

#include "analysis/diagnosis/diagnose.h"
#include "analysis/diagnosis/diagnosis_problem.h"

namespace kneesim::diagnosis::detail {

// the part of an effect the baseline cannot absorb, at every row (row order) [quantity unit]
struct Signal {
  Eigen::VectorXd delta;  // prediction with the effect minus the refitted baseline
  double rms = 0.0;       // in the diagnosis' RMSE measure [rmse_unit]
};
Signal identifiable_signal(const Problem& pb, Effect effect, const Eigen::VectorXd& baseline,
                           const Eigen::VectorXd& effect_params);
// the same for given noise-free values at every row (row order)
Signal identifiable_part(const Problem& pb, const Eigen::VectorXd& truth,
                         const Eigen::VectorXd& baseline);

// the RMS of the fitted error model in the diagnosis' RMSE measure [rmse_unit]
double error_model_rms(const Problem& pb, const Noise& noise, double sigma,
                       const Eigen::VectorXd& prediction);

// `noise`: the noise state of the selected model (the named effect's, or none's)
DetectionResult detection_limits(const Problem& pb, const DiagnosisResult& res,
                                 const Noise& noise, const DiagnosisOptions& options);

}  // namespace kneesim::diagnosis::detail
