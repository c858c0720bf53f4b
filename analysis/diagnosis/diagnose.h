// The generic diagnosis: baseline as practitioners calibrate it, every candidate effect fitted
// by weighted least squares, scored on held-out data (the case's split rule) and by AICc;
// selection with thresholds so that data consistent with the baseline yield "none"; a
// seeded residual bootstrap of the chosen fit; and the gain
// 1 - heldout_rmse_extended / heldout_rmse_baseline.
//
// Noise model (DiagnosisCase::noise_model): one sd per measured quantity, or a sd a + b |f|
// per quantity for wear data, profiled with every fit, in AICc and in the held-out score
// alike: RMSEs are the count-weighted geometric mean of the per-quantity RMSEs (the same
// Gaussian likelihood), printed in the unit of the first quantity in the data (other
// quantities converted by the ratio of their measured RMS values, which cancels in every
// comparison); for one quantity it is the plain RMSE. A pooled case (kinematics: residuals are
// model discrepancy) fits one sd to the converted residuals, and its RMSE is their RMS.
//
// Specimens: when the data name them, every fit carries a specimen random effect (the
// specimen's wear factor scatters multiplicatively), whitened exactly, with its variance ratio
// profiled; otherwise AICc would count a specimen's correlated points as independent.
//
// Selection rule: a candidate is supported when its AICc is below the "none" candidate's by
// more than ic_threshold AND its held-out RMSE is below (1 - heldout_threshold) times the
// "none" candidate's AND below (1 - heldout_threshold) times the trivial predictor's AND none
// of its parameters ended at a search bound; among supported
// candidates the lowest held-out RMSE wins. Both gates are needed: AICc alone rewards
// in-sample fits of specimen scatter, held-out error alone is noisy with few folds. The bound
// rule: a fit that ends at a search bound wants a value outside the searched (physically
// plausible) range, so its parameter is not an estimate and the effect is not a finding (the
// first DM kinematics diagnosis named `restraint` at the stiffness bound x20: a nearly still
// model whose error equalled that of the measured mean). Such a candidate is reported with
// the bound and never named.
//
// Trivial predictor: the measured mean of each quantity (held out: the mean over the fold's
// training rows), or a case's own where its inputs carry most of the answer (forces). Every
// report gives the gain against it, and a candidate must beat it by the same held-out margin
// as it beats "none": a gain that a flat line achieves is not a finding.
//
// Error model (error_model.h, DiagnosisOptions::noise_model): every fit, the baseline's and
// the trivial predictor's included, carries the case's error model: correlated residuals
// (Ornstein-Uhlenbeck along each series, correlation length profiled), specimen random
// effects (wear factor and soak-control offset), and the instrument's nuisance terms (profiled
// by least squares, free or with a prior), which are fitted on the training rows and applied
// to the held-out rows like the model itself (they describe the record, not the model). AICc
// uses the exact Gaussian likelihood of that model and an effective sample size for its
// small-sample term. "white" is the independent-residual model of the previous version.
//
// Detection limits (detection.h): for every candidate, the smallest effect the data could have
// named at their fitted noise, by simulation with the fitted error model.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "analysis/diagnosis/diagnosis_case.h"

namespace kneesim::diagnosis {

struct DiagnosisOptions {
  int bootstrap = 200;              // bootstrap resamples of the chosen fit [-]
  std::uint64_t seed = 1;           // bootstrap seed [-]
  double ic_threshold = 12.0;       // required AICc drop against "none" [-]
  double heldout_threshold = 0.05;  // required relative held-out RMSE drop against "none" [-]
  bool multi_start = true;          // multi-start the full-data fits
  bool trivial_gate = true;         // also require the held-out drop against the trivial predictor
  // rank the supported candidates by AICc (true) or by held-out RMSE (false)
  bool rank_by_aicc = true;
  // supported candidates whose AICc lies within this of the lowest are not told apart by it
  // (Burnham & Anderson: a difference below 2 is no evidence for either); the lower held-out
  // RMSE names one of them [-]
  double tie_aicc = 2.0;
  std::string noise_model = "instrument";     // error model: white, correlated, instrument
  std::map<std::string, double> noise_params; // error-model keys (priors, switches)
  int detection_replicates = 0;     // replicates per candidate of the detection limits, 0: none
  double detection_rate = 0.8;      // fraction of replicates that must name the effect [-]
};

// the profiled error model of one fit
struct NoiseFit {
  double sigma = 0.0;       // sd of the whitened, weighted residuals [rmse_unit]
  double ell = 0.0;         // Ornstein-Uhlenbeck correlation length [series unit]; 0: white
  double nugget = 0.0;      // white fraction of a correlated series' variance [-]
  double rho = 0.0;         // specimen wear-factor variance / sigma^2 (weighted units) [-]
  double rho_offset = 0.0;  // specimen offset variance / sigma^2 (weighted units) [-]
  double n_eff = 0.0;       // effective sample size of AICc's small-sample term [-]
  int parameters = 0;       // error-model parameters counted in AICc [-]
};

// the smallest effect of one candidate the data could have named: along one size parameter
// (the others at their null or initial values), by simulation with the fitted error model
struct DetectionLimit {
  Effect effect = Effect::none;
  std::string param;          // the size parameter
  double null_value = 0.0;    // its value without the effect [param unit]
  int direction = 1;          // +1 above the null value, -1 below
  bool reached = false;       // named in the required fraction within the searched range
  double value = 0.0;         // parameter value at the limit, or the searched bound [param unit]
  double signal_rms = 0.0;    // RMS of the effect's identifiable signal there [rmse_unit]
  double ratio = 0.0;         // signal_rms / the fitted noise RMS [-]
  int replicates = 0;         // simulated data sets [-]
};

struct DetectionResult {
  std::string method;              // "refits of the forward model" or "local linear model"
  double noise_rms = 0.0;          // RMS of the fitted error model [rmse_unit]
  double rate = 0.8;               // required naming fraction [-]
  int replicates = 0;              // per limit [-]
  std::vector<DetectionLimit> limits;
  double seconds = 0.0;            // [s]
};

struct ModelFit {
  Effect effect = Effect::none;
  std::string model;                   // one line describing the model
  std::vector<ParamSpec> specs;        // baseline specs followed by effect specs
  Eigen::VectorXd params;              // [I/O units], specs.size()
  Eigen::VectorXd ci_low, ci_high;     // bootstrap 95 % interval; empty when not bootstrapped
  Eigen::VectorXd predictions;         // model at every measurement [quantity units]
  Eigen::VectorXd heldout_predictions; // each row predicted by the fold that held it out
  double rss = 0.0;                    // weighted residual sum of squares [rmse_unit^2]
  double rmse = 0.0;                   // in-sample [rmse_unit]
  double heldout_rmse = 0.0;           // held-out [rmse_unit]
  double aicc = 0.0;                   // corrected Akaike information criterion [-]
  std::vector<double> noise_sd;        // profiled noise sd per quantity [quantity unit]
  NoiseFit noise;                      // the profiled error model
  std::vector<std::string> nuisance_names;  // the instrument's nuisance terms
  Eigen::VectorXd nuisance;            // their fitted values [term units]
  Eigen::VectorXd nuisance_contribution;  // their sum at every row, part of predictions
                                          // [quantity unit]
  std::vector<int> at_bound;           // indices into specs of parameters at a search bound
  bool passes_gates = false;           // AICc and held-out gates against none passed
  bool beats_trivial = true;           // held-out gate against the trivial predictor passed
};

struct DiagnosisResult {
  std::string rmse_unit;            // quantity whose unit the RMSEs carry, e.g. "volume_mm3"
  std::vector<std::string> quantities;  // measured quantities, first = rmse_unit
  NoiseModel noise_model = NoiseModel::per_quantity;  // the residual model used
  ErrorModel error_model;           // the error model used (error_model.h)
  std::string series_unit;          // unit of the correlation length
  bool specimens = false;           // specimen random effects fitted
  DetectionResult detection;        // detection limits (empty unless requested)
  Eigen::VectorXd weights;          // unit conversion into rmse_unit per measurement [-]
  ModelFit baseline;                // practitioner's calibration, not refitted
  ModelFit trivial;                 // the measured mean of each quantity, or the case's own
  std::vector<ModelFit> candidates; // "none" first, then the case's candidates
  int selected = 0;                 // index into candidates
  // a supported candidate within tie_aicc of the named one's AICc (the data's likelihood does
  // not tell the two apart; the held-out RMSE named `selected`), or -1
  int tied_with = -1;
  double tie_band = 2.0;            // the AICc band of the selection (options.tie_aicc) [-]
  double gain = 0.0;                // 1 - heldout extended / heldout baseline [-]
  double gain_vs_trivial = 0.0;     // 1 - heldout extended / heldout trivial [-]
  double seconds = 0.0;             // wall time [s]
  const ModelFit& extended() const { return candidates[static_cast<size_t>(selected)]; }
  Effect effect() const { return extended().effect; }
};

// Indices of the parameters that ended at a search bound: within 0.5 % of the searched range
// of the bound, measured in the fitted space (log for log-scale parameters); a lower bound
// marked lower_is_limit is a physical limit and does not count.
std::vector<int> find_params_at_bound(const std::vector<ParamSpec>& specs,
                                      const Eigen::VectorXd& params);

// the selection gates: the AICc drop and the held-out drop against "none"; the held-out drop
// against the trivial predictor
bool passes_gates(const ModelFit& m, const ModelFit& none, const DiagnosisOptions& options);
// names one of the supported candidates (indices into res.candidates that passed every gate,
// with no parameter at a search bound): the lowest AICc, or within options.tie_aicc of it the
// lowest held-out RMSE; sets res.selected (0, none, when the list is empty) and res.tied_with
void select_among_supported(DiagnosisResult& res, const std::vector<int>& supported,
                            const DiagnosisOptions& options);
bool beats_trivial(const ModelFit& m, const ModelFit& trivial, const DiagnosisOptions& options);
// a candidate (not none) that may be named: both gates and the trivial gate passed, no
// parameter at a search bound (the flags set by diagnose())
bool is_supported(const ModelFit& m);

// runs the diagnosis; throws InputError when the data have fewer measurements than a
// candidate and the error model need (n > parameters + 2 for AICc), or for an unknown noise
// model or key
DiagnosisResult diagnose(const DiagnosisCase& c, const DiagnosisOptions& options = {});

// RMS of the part of an effect the baseline cannot absorb: the case's prediction with the
// effect minus the baseline model (and the free nuisance terms) refitted to it by least
// squares, in the diagnosis' RMSE measure (rmse_unit); the size of a hidden effect as the
// detection limits measure it
// the diagnosis' RMSE measure (rmse_unit) of residuals given at every measured row of `c`:
// the count-weighted geometric mean of the per-quantity RMS values converted into rmse_unit,
// or the RMS of the converted residuals for pooled noise
double rmse_measure(const DiagnosisCase& c, const Eigen::VectorXd& residuals,
                    const DiagnosisOptions& options = {});

// the same for given noise-free values at every measured row (e.g. made by another forward
// path): their RMS departure from the baseline refitted to them, starting from `baseline`
double identifiable_rms_of(const DiagnosisCase& c, const Eigen::VectorXd& values,
                           const Eigen::VectorXd& baseline, const DiagnosisOptions& options = {});

double identifiable_signal_rms(const DiagnosisCase& c, Effect effect,
                               const Eigen::VectorXd& baseline,
                               const Eigen::VectorXd& effect_params,
                               const DiagnosisOptions& options = {});

}  // namespace kneesim::diagnosis
