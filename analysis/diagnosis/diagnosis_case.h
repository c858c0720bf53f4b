// The interface every diagnosis case implements (block-on-ring now; knee wear and kinematics
// later). A case is four things: the measured data, a forward model parameterised by
// baseline parameters plus the parameters of one effect, the practitioner's calibration rule
// for the baseline, and the held-out split rule. diagnose() (diagnose.h) is generic over it:
// it fits every candidate effect, scores it on held-out data and with an information
// criterion, picks one or "none", bootstraps the chosen fit and measures the gain.
//
// Design: a struct of std::function rather than a virtual base class, so a case is assembled
// from lambdas that capture its own state (tables, configs, a simulator) and can be built in a
// few lines by a test. Parameters cross the interface in I/O units (mm^3/(N mm), cycles, s),
// the units reports print; the case converts to SI for its simulator. Rejected: one generic
// "fit everything" curve model inside the diagnosis, because the issue requires every effect
// to be a real extension of the forward simulators.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "analysis/diagnosis/effect.h"
#include "analysis/diagnosis/error_model.h"
#include "analysis/diagnosis/fit.h"

namespace kneesim::diagnosis {

struct Measurement {
  std::string group;     // condition the forward model distinguishes (load, gait) e.g. "225 N"
  std::string specimen;  // specimen id within the group; "" when the data have none
  std::string quantity;  // measured quantity with unit, e.g. "volume_mm3", "depth_mm"
  double x = 0.0;        // abscissa in I/O units (cycles, gait_pct)
  double value = 0.0;    // measured value in the quantity's unit
  int row = 0;           // 1-based line in the source file (header = line 1)
};

struct MeasuredData {
  std::string source;                 // file name, for messages and reports
  std::string x_name;                 // abscissa name with unit, e.g. "cycles"
  std::vector<Measurement> rows;
};

// one held-out split: fit on `train`, predict `test` (indices into MeasuredData::rows)
struct Fold {
  std::string name;        // e.g. "specimen 225 N/s2" or "load 130 N"
  std::vector<int> train;
  std::vector<int> test;
};

// a model curve for plots
struct CurvePoint {
  std::string group;     // as Measurement::group
  std::string quantity;  // as Measurement::quantity
  double x = 0.0;        // abscissa [x_name unit]
  double value = 0.0;    // model value [quantity unit]
};

// The residual model of a case's fits (diagnose.h).
//   pooled: one sd for all rows, quantities converted into the first one's unit by the ratio of
//     their measured RMS values; for residuals that are model discrepancy rather than
//     measurement noise (one measured kinematics curve against a rig model: AP and IE are
//     put on an equal footing by their magnitude, and the quantity the model misses worst is
//     not down-weighted for it)
//   per_quantity: one sd per measured quantity, profiled
//   proportional: per quantity a sd a + b |value|, profiled (repeated wear measurements: a
//     balance or profilometer error plus a part proportional to the amount); falls back to
//     per_quantity when a quantity has fewer than 20 measurements
enum class NoiseModel { pooled, per_quantity, proportional };

struct DiagnosisCase {
  std::string name;                    // case name, e.g. "bor"
  MeasuredData measured;
  std::string baseline_model;          // one line: the practitioner's model and calibration
  std::vector<ParamSpec> baseline_params;  // refitted in every candidate (e.g. k)
  int specimen_param = 0;              // baseline parameter that scatters multiplicatively
                                       // between specimens (the random effect's direction)
  std::vector<Effect> candidates;      // effects applicable to these data (without none)
  std::string split_rule;              // e.g. "leave-one-specimen-out"
  std::vector<Fold> folds;             // the held-out split rule, applied
  FitControl fit_control;              // iteration cap of every fit (simulation-based cases)
  // effects fitted multi-start even when the options turn multi-start off: discrete
  // alternatives a local fit cannot cross to (the sign of a load)
  std::set<Effect> multi_start_effects;
  NoiseModel noise_model = NoiseModel::per_quantity;  // see NoiseModel
  // the case's full error model (error_model.h: correlation, specimen offset, the instrument's
  // nuisance terms); diagnose() reduces it to DiagnosisOptions::noise_model
  ErrorModel error_model;
  // the series of the residual correlation: a key per row (default: group/specimen/quantity)
  // and the abscissa along it (default: x), and the abscissa's unit for reports (default: the
  // data's x_name)
  std::vector<std::string> series_key;
  std::vector<double> series_x;
  std::string series_unit;
  // every forward evaluation is a full simulation: the detection-limit simulation then uses a
  // local linear model of each candidate about its no-effect point (detection.h)
  bool expensive_forward = false;
  // realizations (every row) of the forward model's own error against a direct simulation:
  // the detection replicates add one, drawn at random, to each simulated data set, since a
  // real effect differs from the model's by at least that much (forces: a direct simulation
  // between grid values against the interpolated grid); empty: the model's effect is taken as
  // exact
  std::vector<Eigen::VectorXd> forward_error_draws;

  // effect parameter specs for this case (bounds, starts); default: effect_info(e).params
  std::function<std::vector<ParamSpec>(Effect)> effect_params;
  // forward model: predictions for measurement indices `rows` [quantity units]
  std::function<Eigen::VectorXd(Effect effect, const Eigen::VectorXd& baseline,
                                const Eigen::VectorXd& effect_params,
                                const std::vector<int>& rows)>
      predict;
  // optional: runs the forward model ahead for several effect-parameter vectors (I/O units)
  // that predict() will be asked for next (a Jacobian's columns, multi-starts, the detection
  // limit's linearization); a simulation-based case runs them in parallel into its cache. It
  // must not change any prediction, only when it is computed.
  std::function<void(Effect effect, const std::vector<Eigen::VectorXd>& effect_params)> prefetch;
  // the practitioner's calibration of the baseline parameters from the `train` rows
  std::function<Eigen::VectorXd(const std::vector<int>& train)> calibrate_baseline;
  // case-specific remarks appended to an effect's model line (fixed parameters, references)
  std::map<Effect, std::string> model_notes;
  // the trivial predictor (optional; default: each quantity's measured mean over the training
  // rows): a case whose inputs already carry most of the answer names a stronger one (forces:
  // the training rows' mean medial share times each row's measured total). Predictions for
  // `rows` from the measured values `y` (all rows; replicates of the detection-limit simulation
  // pass their own) of the `train` rows [quantity units].
  std::string trivial_model;
  std::function<Eigen::VectorXd(const Eigen::VectorXd& y, const std::vector<int>& train,
                                const std::vector<int>& rows)>
      trivial_predict;
  // dense model curves for plots (optional)
  std::function<std::vector<CurvePoint>(Effect effect, const Eigen::VectorXd& baseline,
                                        const Eigen::VectorXd& effect_params)>
      curves;
};

// leave-one-group-out folds: one fold per specimen ("group/specimen") when per_specimen,
// else one per group; fold names are "specimen <key>" or "<group_word> <key>"
std::vector<Fold> make_leave_one_out_folds(const std::vector<Measurement>& rows, bool per_specimen,
                                           const std::string& group_word);

// effect parameter specs of `effect` in case `c` (its override or the library default)
std::vector<ParamSpec> case_effect_params(const DiagnosisCase& c, Effect effect);

}  // namespace kneesim::diagnosis
