#include "analysis/diagnosis/diagnose.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>

#include "analysis/diagnosis/detection.h"
#include "analysis/diagnosis/diagnosis_problem.h"
#include "analysis/diagnosis/fit.h"
#include "engine/errors.h"

namespace kneesim::diagnosis {

std::vector<Fold> make_leave_one_out_folds(const std::vector<Measurement>& rows, bool per_specimen,
                                           const std::string& group_word) {
  std::map<std::string, std::vector<int>> groups;
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& m = rows[i];
    groups[per_specimen ? m.group + "/" + m.specimen : m.group].push_back(static_cast<int>(i));
  }
  std::vector<Fold> folds;
  for (const auto& [key, members] : groups) {
    Fold f;
    f.name = (per_specimen ? "specimen " : group_word + " ") + key;
    f.test = members;
    for (size_t i = 0; i < rows.size(); ++i) {
      if (std::find(members.begin(), members.end(), static_cast<int>(i)) == members.end()) {
        f.train.push_back(static_cast<int>(i));
      }
    }
    folds.push_back(std::move(f));
  }
  return folds;
}

std::vector<int> find_params_at_bound(const std::vector<ParamSpec>& specs,
                                      const Eigen::VectorXd& params) {
  constexpr double kBoundFraction = 0.005;  // of the searched range, in the fitted space
  std::vector<int> out;
  for (size_t i = 0; i < specs.size() && static_cast<Eigen::Index>(i) < params.size(); ++i) {
    const ParamSpec& s = specs[i];
    const bool log = s.log_scale && s.lower > 0.0;
    auto t = [log](double v) { return log ? std::log(std::max(v, 1e-300)) : v; };
    const double lo = t(s.lower), hi = t(s.upper), v = t(params[static_cast<Eigen::Index>(i)]);
    const double tol = kBoundFraction * (hi - lo);
    if ((!s.lower_is_limit && v <= lo + tol) || v >= hi - tol) out.push_back(static_cast<int>(i));
  }
  return out;
}

std::vector<ParamSpec> case_effect_params(const DiagnosisCase& c, Effect effect) {
  if (effect == Effect::none) return {};
  return c.effect_params ? c.effect_params(effect) : effect_info(effect).params;
}

DiagnosisResult diagnose(const DiagnosisCase& c, const DiagnosisOptions& options) {
  using namespace detail;
  const auto t0 = std::chrono::steady_clock::now();
  Problem pb = make_problem(c, options);
  const auto& rows = c.measured.rows;
  DiagnosisResult res;
  res.rmse_unit = rows.front().quantity;
  res.quantities = pb.quantity_names;
  res.weights = pb.unit;
  res.noise_model = pb.noise;
  res.error_model = pb.em;
  res.series_unit = c.series_unit.empty() ? c.measured.x_name : c.series_unit;
  res.specimens = pb.random_effect;

  // the practitioner's calibration, without the error model, for the random-effect direction:
  // d prediction / d ln(specimen parameter) (for depth this is not the depth itself: depth
  // grows less than proportionally with volume); a case without baseline parameters (forces)
  // has no specimen direction
  const Eigen::VectorXd calibrated = c.calibrate_baseline(all_rows(rows.size()));
  if (c.specimen_param < static_cast<int>(c.baseline_params.size())) {
    Eigen::VectorXd b2 = calibrated;
    b2[c.specimen_param] *= 1.01;
    const Eigen::VectorXd none;
    const auto all = all_rows(rows.size());
    const Eigen::VectorXd base = c.predict(Effect::none, calibrated, none, all);
    const Eigen::VectorXd up = c.predict(Effect::none, b2, none, all);
    pb.dg = (up - base) / std::log(1.01);
  }
  // proportional noise with specimens: the noise line of each quantity is a property of the
  // measurement, so it is estimated once, from the pure error (each specimen's measurements
  // about its own scaled baseline curve, which absorbs any level difference between specimens
  // and conditions), and shared by every candidate; only the common sigma is profiled per
  // candidate. Estimated per candidate from its own residuals instead, the line differed
  // between candidates and added up to 5 to a clean data set's dAICc.
  if (pb.noise == NoiseModel::proportional && pb.random_effect) {
    const Eigen::VectorXd none;
    Eigen::VectorXd own = c.predict(Effect::none, calibrated, none, all_rows(rows.size()));
    for (const auto& cl : pb.clusters) {
      for (int q = 0; q < pb.quantities(); ++q) {
        double yf = 0.0, ff = 0.0;
        for (int i : cl) {
          if (pb.quantity[static_cast<size_t>(i)] != q) continue;
          yf += pb.y[i] * own[i];
          ff += own[i] * own[i];
        }
        const double scale = ff > 0.0 ? yf / ff : 1.0;
        for (int i : cl) {
          if (pb.quantity[static_cast<size_t>(i)] == q) own[i] *= scale;
        }
      }
    }
    pb.fixed_w = proportional_weights(pb, own);
  }
  std::vector<Effect> effects = {Effect::none};
  effects.insert(effects.end(), c.candidates.begin(), c.candidates.end());
  std::vector<Noise> noises(effects.size());
  res.candidates.resize(effects.size());
  if (c.fit_control.threads > 1) {  // the candidates' fits side by side, results in order
    std::vector<std::future<ModelFit>> fits;
    for (size_t i = 0; i < effects.size(); ++i) {
      fits.push_back(std::async(std::launch::async, [&, i] {
        return fit_candidate(pb, pb.y, effects[i], calibrated, options, &noises[i]);
      }));
    }
    for (size_t i = 0; i < effects.size(); ++i) res.candidates[i] = fits[i].get();
  } else {
    for (size_t i = 0; i < effects.size(); ++i) {
      res.candidates[i] = fit_candidate(pb, pb.y, effects[i], calibrated, options, &noises[i]);
    }
  }
  // the baseline and the trivial predictor carry the error model of the refitted baseline
  // (its nuisance terms fitted on the training rows like every model's)
  res.baseline = practitioner_baseline(pb, noises.front());
  res.trivial = trivial_predictor(pb, pb.y, noises.front());

  // selection against "none"
  const ModelFit& none = res.candidates.front();
  res.selected = 0;
  for (auto& m : res.candidates) m.at_bound = find_params_at_bound(m.specs, m.params);
  std::vector<int> supported;
  for (size_t i = 1; i < res.candidates.size(); ++i) {
    ModelFit& m = res.candidates[i];
    m.passes_gates = passes_gates(m, none, options);
    // a gain the trivial predictor also achieves is not a finding: the same held-out margin
    // against it (binds only where the baseline predicts worse than the trivial predictor)
    m.beats_trivial = beats_trivial(m, res.trivial, options);
    if (is_supported(m)) supported.push_back(static_cast<int>(i));
  }
  select_among_supported(res, supported, options);
  bootstrap(pb, res.candidates[static_cast<size_t>(res.selected)],
            noises[static_cast<size_t>(res.selected)], options);
  res.gain = (res.baseline.heldout_rmse > 0.0)
                 ? 1.0 - res.extended().heldout_rmse / res.baseline.heldout_rmse
                 : 0.0;
  res.gain_vs_trivial = (res.trivial.heldout_rmse > 0.0)
                            ? 1.0 - res.extended().heldout_rmse / res.trivial.heldout_rmse
                            : 0.0;
  if (options.detection_replicates > 0) {
    res.detection = detection_limits(pb, res, noises[static_cast<size_t>(res.selected)], options);
  }
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

void select_among_supported(DiagnosisResult& res, const std::vector<int>& supported,
                            const DiagnosisOptions& options) {
  res.selected = 0;
  res.tied_with = -1;
  res.tie_band = options.rank_by_aicc ? options.tie_aicc : 0.0;
  if (supported.empty()) return;
  const auto& c = res.candidates;
  auto at = [&](int i) -> const ModelFit& { return c[static_cast<size_t>(i)]; };
  if (!options.rank_by_aicc) {
    res.selected = *std::min_element(supported.begin(), supported.end(), [&](int a, int b) {
      return at(a).heldout_rmse < at(b).heldout_rmse;
    });
    return;
  }
  // the lowest AICc, then within tie_aicc of it the lowest held-out RMSE (candidate order
  // breaks exact ties, so the answer is deterministic)
  const int lowest = *std::min_element(supported.begin(), supported.end(),
                                       [&](int a, int b) { return at(a).aicc < at(b).aicc; });
  std::vector<int> band;
  for (int i : supported) {
    if (at(i).aicc <= at(lowest).aicc + options.tie_aicc) band.push_back(i);
  }
  res.selected = *std::min_element(band.begin(), band.end(), [&](int a, int b) {
    return at(a).heldout_rmse < at(b).heldout_rmse;
  });
  for (int i : band) {  // the runner-up: the lowest AICc of the others in the band
    if (i != res.selected && (res.tied_with < 0 || at(i).aicc < at(res.tied_with).aicc)) res.tied_with = i;
  }
}

bool is_supported(const ModelFit& m) {
  return m.effect != Effect::none && m.passes_gates && m.beats_trivial && m.at_bound.empty();
}

bool passes_gates(const ModelFit& m, const ModelFit& none, const DiagnosisOptions& options) {
  const bool ic_ok = m.aicc < none.aicc - options.ic_threshold;
  const bool heldout_ok = m.heldout_rmse < (1.0 - options.heldout_threshold) * none.heldout_rmse;
  return ic_ok && heldout_ok;
}

bool beats_trivial(const ModelFit& m, const ModelFit& trivial, const DiagnosisOptions& options) {
  return !options.trivial_gate ||
         m.heldout_rmse < (1.0 - options.heldout_threshold) * trivial.heldout_rmse;
}

double rmse_measure(const DiagnosisCase& c, const Eigen::VectorXd& residuals,
                    const DiagnosisOptions& options) {
  const detail::Problem pb = detail::make_problem(c, options);
  return detail::score(pb, residuals, Eigen::VectorXd::Zero(residuals.size()));
}

double identifiable_rms_of(const DiagnosisCase& c, const Eigen::VectorXd& values,
                           const Eigen::VectorXd& baseline, const DiagnosisOptions& options) {
  const detail::Problem pb = detail::make_problem(c, options);
  return detail::identifiable_part(pb, values, baseline).rms;
}

double identifiable_signal_rms(const DiagnosisCase& c, Effect effect,
                               const Eigen::VectorXd& baseline,
                               const Eigen::VectorXd& effect_params,
                               const DiagnosisOptions& options) {
  const detail::Problem pb = detail::make_problem(c, options);
  return detail::identifiable_signal(pb, effect, baseline, effect_params).rms;
}

}  // namespace kneesim::diagnosis
