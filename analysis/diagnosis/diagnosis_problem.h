// Internal to the diagnosis framework (diagnose.cpp, detection.cpp): the measurements with
// their noise, specimen and series structure, and the fits under the error model
// (error_model.h). Not part of the library's interface; cases use diagnose.h.
//
// Noise (DiagnosisCase::noise_model): one sd for all rows (pooled), one per measured quantity,
// or, when the measurement error grows with the measured amount (wear: a balance or
// profilometer error plus a relative part), a sd a_q + b_q |f| per quantity. Residuals (own
// units) are weighted by w_i, sd_i = sigma / w_i; w_i starts at unit_i, which converts quantity
// q into the first quantity's unit by the ratio of the measured RMS values (the conversion only
// sets the unit the RMSEs are printed in; the likelihood does not depend on it), and is
// re-estimated from the fit's residuals, or, for the proportional line with specimens, once
// from the pure error and shared by every candidate (diagnose()). Why: volume and depth (AP
// and IE) are measured with different instruments and precisions; with one pooled variance the
// noisier quantity is over-weighted, and an effect that changes only that quantity (creep:
// depth) gains likelihood by fitting its noise.
//
// Specimens: specimens of one material scatter in wear factor (multiplicatively), so the
// residuals of one specimen are correlated; when specimens are given, every model is fitted
// with a specimen random effect: y_s = f_s + u_s dg_s + e, u_s ~ N(0, tau^2), dg_s = derivative
// of the specimen's baseline curve with respect to ln k; with the instrument error model also
// a soak-control offset per specimen on the volume rows. Without them, AICc treats the 4-8
// correlated points of a specimen as independent and mistakes specimen scatter between loads
// for a pressure effect.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "analysis/diagnosis/diagnose.h"
#include "analysis/diagnosis/error_model.h"
#include "analysis/diagnosis/fit.h"

namespace kneesim::diagnosis::detail {

struct Problem {
  const DiagnosisCase& c;
  Eigen::VectorXd y;                       // measured values
  Eigen::VectorXd unit;                    // quantity -> first quantity's unit, per row
  std::vector<int> quantity;               // quantity index per row
  std::vector<std::string> quantity_names; // first = the RMSE unit
  std::vector<std::vector<int>> clusters;  // specimens, series, or one row each
  Eigen::VectorXd dg;                      // random-effect direction per row (unweighted)
  bool random_effect = false;              // specimens given: fit tau too
  NoiseModel noise = NoiseModel::per_quantity;  // the case's, with the row-count fallback
  Eigen::VectorXd fixed_w;                 // row weights shared by every candidate, or empty
  ErrorModel em;                           // the selected error model
  std::vector<int> series;                 // series index per row
  std::vector<double> sx;                  // abscissa of the correlation per row
  std::vector<char> offset_rows;           // 1 where the specimen offset acts
  double ell_lo = 0.0, ell_hi = 0.0;       // searched correlation lengths [series unit]
  int max_params = 0;                      // most regression parameters of any candidate
                                           // (the floor of n_eff)
  int quantities() const { return static_cast<int>(quantity_names.size()); }
};

// the problem without the random-effect direction (set by diagnose() from the baseline);
// throws InputError for an unknown noise model or key
Problem make_problem(const DiagnosisCase& c, const DiagnosisOptions& options);

// a fit's noise state
struct Noise {
  Eigen::VectorXd w;      // per row [1/quantity unit, up to the common sigma]
  double rho = 0.0;       // specimen slope variance ratio [-]
  double rho_offset = 0.0;  // specimen offset variance ratio [-]
  double ell = 0.0;       // correlation length [series unit]
  double nugget = 0.0;    // white fraction of a correlated series' variance [-]
  double sigma = 0.0;     // whitened sd setting the nuisance priors' weight; 0: priors off
};

// one evaluation: predictions of the flattened rows, the nuisance fit, the whitened residuals
struct Eval {
  Eigen::VectorXd pred;   // model at the rows (without nuisance)
  Eigen::VectorXd beta;   // nuisance terms [term units]
  Eigen::VectorXd resid;  // whitened residuals after the nuisance terms
  double rss = std::numeric_limits<double>::infinity();  // |resid|^2
  double penalty = 0.0;   // sum over priored terms of (beta / prior sd)^2
};

// the proportional noise line's row weights from a prediction (diagnose(): the pure error)
Eigen::VectorXd proportional_weights(const Problem& pb, const Eigen::VectorXd& pred);

std::vector<int> flatten(const std::vector<std::vector<int>>& clusters);
std::vector<int> all_rows(size_t n);
std::vector<std::vector<int>> clusters_of(const Problem& pb, const std::vector<int>& rows);

Whitener make_whitener(const Problem& pb, const std::vector<std::vector<int>>& clusters,
                       const Noise& noise);
Eigen::VectorXd predict(const Problem& pb, Effect e, const Eigen::VectorXd& params,
                        const std::vector<int>& rows);
// the nuisance columns at `rows` given the prediction there, unweighted [quantity unit]
Eigen::MatrixXd nuisance_columns(const Problem& pb, const std::vector<int>& rows,
                                 const Eigen::VectorXd& pred);
// the error model's treatment of a given prediction at the clusters' flattened rows
Eval evaluate_prediction(const Problem& pb, const Eigen::VectorXd& y,
                         const std::vector<int>& rows, const Eigen::VectorXd& pred,
                         const Whitener& wh, const Noise& noise);
Eval evaluate(const Problem& pb, const Eigen::VectorXd& y, Effect e,
              const Eigen::VectorXd& params, const std::vector<std::vector<int>>& clusters,
              const Whitener& wh, const Noise& noise);

// least-squares fit of `e` on the clusters' rows at a fixed noise state
struct FitState {
  FitResult fit;
  Eval eval;
};
FitState fit_clusters(const Problem& pb, const Eigen::VectorXd& y, Effect e,
                      const std::vector<ParamSpec>& specs, const Eigen::VectorXd& start,
                      const std::vector<std::vector<int>>& clusters, const Noise& noise,
                      bool multi);

// -2 log L (profiled over sigma, constants dropped) of a full-data evaluation
double neg2_log_likelihood(const Problem& pb, const Eval& ev, const Whitener& wh,
                           const Noise& noise);
// error-model parameters counted in AICc (sds, variance ratios, correlation length, nuisance)
int error_parameters(const Problem& pb);
double effective_n(const Problem& pb, const Noise& noise);
// the regression parameters of a model with `model_params` parameters: those, the free
// nuisance terms and the residual scale (the k of Hurvich and Tsai's small-sample term)
int regression_parameters(const Problem& pb, size_t model_params);
// AICc = -2 log L + 2 k + 2 k_r (k_r + 1) / (n_eff - k_r - 1): k every estimated parameter, k_r
// the regression parameters, n_eff the effective sample size of the correlated residuals
double aicc_of(double neg2, int k, int k_r, double n_eff);

// the score of a prediction of all rows (diagnose.h: count-weighted geometric mean of the
// per-quantity RMSEs in rmse_unit, or the RMS of converted residuals for pooled noise)
double score(const Problem& pb, const Eigen::VectorXd& y, const Eigen::VectorXd& pred);

// a candidate fitted to y with its error model profiled; multi-start from the baseline's
// calibrated values; held-out predictions by refitting on each fold
ModelFit fit_candidate(const Problem& pb, const Eigen::VectorXd& y, Effect e,
                       const Eigen::VectorXd& calibrated, const DiagnosisOptions& opt,
                       Noise* noise_out);
// the same with the noise state fixed (detection-limit replicates): one fit from `start`
ModelFit fit_candidate_fixed_noise(const Problem& pb, const Eigen::VectorXd& y, Effect e,
                                   const Eigen::VectorXd& start, const Noise& noise,
                                   bool heldout);
// the held-out prediction of `test` rows from a model's prediction there: the prior-bound
// nuisance terms from the training rows (`beta_train`: the instrument's calibration, the same
// over the record; at their prior mean 0 where NuisanceTerm::carried_to_heldout is false) and
// the free ones (an offset, a drift: not predictable from other rows)
// fitted on the test rows themselves, for every model and the trivial predictor alike
Eigen::VectorXd heldout_with_nuisance(const Problem& pb, const Eigen::VectorXd& y,
                                      const std::vector<int>& test, const Eigen::VectorXd& pred,
                                      const Eigen::VectorXd& beta_train, const Noise& noise);
// predictions of held-out rows for each fold, refitting from `start` at a fixed noise state;
// nuisance terms as heldout_with_nuisance
Eigen::VectorXd heldout_predictions(const Problem& pb, const Eigen::VectorXd& y, Effect e,
                                    const std::vector<ParamSpec>& specs,
                                    const Eigen::VectorXd& start, const Noise& noise);
// the practitioner's baseline and the trivial predictor (with the nuisance terms of `noise`)
ModelFit practitioner_baseline(const Problem& pb, const Noise& noise);
ModelFit trivial_predictor(const Problem& pb, const Eigen::VectorXd& y, const Noise& noise);
void bootstrap(const Problem& pb, ModelFit& m, const Noise& noise, const DiagnosisOptions& opt);
std::vector<ParamSpec> candidate_specs(const Problem& pb, Effect e);

}  // namespace kneesim::diagnosis::detail
