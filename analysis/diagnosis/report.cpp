#include "analysis/diagnosis/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace kneesim::diagnosis {
namespace {

std::string num(double v, const char* f = "%.4g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

nlohmann::json params_json(const ModelFit& m) {
  nlohmann::json p = nlohmann::json::object();
  for (size_t i = 0; i < m.specs.size(); ++i) p[m.specs[i].name] = m.params[static_cast<Eigen::Index>(i)];
  return p;
}

// names of the parameters at a search bound, with value and bound, e.g. "s = 20 (upper bound
// 20)"; empty when none is
std::string at_bound_text(const ModelFit& m) {
  std::string out;
  for (int i : m.at_bound) {
    const ParamSpec& s = m.specs[static_cast<size_t>(i)];
    const double v = m.params[i];
    const bool upper = std::abs(v - s.upper) < std::abs(v - s.lower);
    out += (out.empty() ? "" : ", ") + s.name + " = " + num(v) + " (" +
           (upper ? "upper" : "lower") + " search bound " + num(upper ? s.upper : s.lower) + ")";
  }
  return out;
}

std::string verdict(const DiagnosisResult& r, size_t i) {
  const ModelFit& m = r.candidates[i];
  if (m.effect == Effect::none) return "reference";
  if (static_cast<int>(i) == r.selected) {
    if (r.tied_with < 0) return "named";
    const ModelFit& t = r.candidates[static_cast<size_t>(r.tied_with)];
    return "named (AICc " + num(m.aicc - t.aicc, "%+.1f") + " against `" +
           std::string(effect_name(t.effect)) + "`, within the tie band: the lower held-out RMSE decided)";
  }
  if (!m.at_bound.empty()) {
    return std::string(m.passes_gates ? "passed the gates but " : "") + "at a search bound: " +
           at_bound_text(m) + "; not named";
  }
  if (m.passes_gates && !m.beats_trivial) {
    return "passed the gates against none but not against the trivial predictor: not named";
  }
  if (!m.passes_gates) return "not supported";
  double lowest = m.aicc;  // the lowest AICc of the supported candidates
  for (const auto& o : r.candidates) {
    if (is_supported(o)) lowest = std::min(lowest, o.aicc);
  }
  return m.aicc <= lowest + r.tie_band
             ? "supported, as likely as the named one (AICc within the tie band) but a higher held-out RMSE"
             : "supported, higher AICc than the named one";
}

Eigen::VectorXd baseline_of(const DiagnosisCase& c, const ModelFit& m) {
  return m.params.head(static_cast<Eigen::Index>(c.baseline_params.size()));
}

Eigen::VectorXd effect_of(const DiagnosisCase& c, const ModelFit& m) {
  const auto nb = static_cast<Eigen::Index>(c.baseline_params.size());
  return m.params.tail(m.params.size() - nb);
}

std::string error_model_markdown(const DiagnosisResult& r) {
  const ModelFit& none = r.candidates.front();
  const ModelFit& e = r.extended();
  std::string md = "\n## Error model\n\nNoise model `" + r.error_model.name + "` (`--noise-model`): ";
  std::vector<std::string> parts;
  if (r.error_model.correlation == Correlation::ou) {
    parts.push_back("residuals correlated along each series (Ornstein-Uhlenbeck plus a white "
                    "part, profiled: correlation length " + num(none.noise.ell) + " " +
                    r.series_unit + " and white fraction " + num(none.noise.nugget, "%.2f") +
                    " for none" +
                    (e.effect == Effect::none
                         ? std::string()
                         : ", " + num(e.noise.ell) + " and " + num(e.noise.nugget, "%.2f") +
                               " for " + std::string(effect_name(e.effect))) +
                    ")");
  }
  if (r.specimens) {
    parts.push_back(std::string("specimen random effects (wear factor") +
                    (r.error_model.specimen_offset ? " and a soak-control offset on the volume" : "") +
                    ")");
  }
  if (!r.error_model.nuisance.empty()) parts.push_back("the instrument's nuisance terms below");
  if (parts.empty()) parts.push_back("independent residuals");
  for (size_t i = 0; i < parts.size(); ++i) md += (i ? "; " : "") + parts[i];
  md += ". Effective sample size of AICc's small-sample term " + num(none.noise.n_eff, "%.1f") +
        " of " + std::to_string(none.predictions.size()) + " measurements; the error model "
        "counts " + std::to_string(none.noise.parameters) +
        (none.noise.parameters == 1 ? " parameter" : " parameters") + " in every candidate.\n";
  const bool named = e.effect != Effect::none;
  if (!r.error_model.nuisance.empty()) {
    md += "\nNuisance terms (fitted with every model on its training rows, applied to the "
          "held-out rows; reported, never named as causes):\n\n| term | prior sd | none | " +
          (named ? std::string(effect_name(e.effect)) + " | " : std::string()) + "meaning |\n|---|---|---|" +
          (named ? "---|" : "") + "---|\n";
    for (size_t k = 0; k < r.error_model.nuisance.size(); ++k) {
      const auto& t = r.error_model.nuisance[k];
      const auto kk = static_cast<Eigen::Index>(k);
      md += "| " + t.name + " | " + (t.prior_sd > 0.0 ? num(t.prior_sd) + " (`" + t.prior_key + "`)"
                                                     : std::string("free")) +
            " | " + (kk < none.nuisance.size() ? num(none.nuisance[kk]) : std::string("-")) + " | " +
            (named ? (kk < e.nuisance.size() ? num(e.nuisance[kk]) : std::string("-")) + " | "
                   : std::string()) +
            t.description + " |\n";
    }
  }
  return md;
}

std::string detection_markdown(const DiagnosisResult& r) {
  if (r.detection.limits.empty()) return "";
  std::string md = "\n## Detection limits\n\n";
  if (r.effect() == Effect::none) {
    md += "Named `none`: **no effect larger than the limits below.** ";
  }
  md += "For each candidate and each parameter that sets its size, the smallest departure from "
        "its null value that the selection rule names in " + num(100.0 * r.detection.rate, "%.0f") +
        " % of " + std::to_string(r.detection.replicates) + " data sets simulated with the fitted "
        "error model (the refitted baseline plus the effect plus noise drawn from the profiled "
        "covariance and the nuisance priors; " + r.detection.method + "; " +
        num(r.detection.seconds, "%.1f") + " s). Signal: RMS of the part of the effect the "
        "baseline cannot absorb; fitted noise RMS " + num(r.detection.noise_rms) + " " +
        r.rmse_unit + ".\n\n| effect | parameter (null value) | limit | signal RMS | signal / "
        "noise |\n|---|---|---|---|---|\n";
  for (const auto& l : r.detection.limits) {
    md += "| " + std::string(effect_name(l.effect)) + " | " + l.param + " (" + num(l.null_value) +
          ") | " + (l.reached ? num(l.value) : "not named up to " + num(l.value) + " (searched range)") +
          " | " + num(l.signal_rms) + " | " + num(l.ratio, "%.2f") + " |\n";
  }
  return md;
}

}  // namespace

nlohmann::json diagnosis_json(const DiagnosisCase& c, const DiagnosisResult& r) {
  nlohmann::json j;
  j["case"] = c.name;
  j["measured"] = c.measured.source;
  j["split_rule"] = c.split_rule;
  j["rmse_unit"] = r.rmse_unit;
  j["baseline"] = {{"model", r.baseline.model},
                   {"params", params_json(r.baseline)},
                   {"rmse", r.baseline.rmse},
                   {"heldout_rmse", r.baseline.heldout_rmse}};
  const ModelFit& e = r.extended();
  j["effect"] = std::string(effect_name(e.effect));
  nlohmann::json ci = nlohmann::json::object();
  for (size_t i = 0; i < e.specs.size() && e.ci_low.size() > 0; ++i) {
    ci[e.specs[i].name] = {e.ci_low[static_cast<Eigen::Index>(i)], e.ci_high[static_cast<Eigen::Index>(i)]};
  }
  j["extended"] = {{"model", e.model},
                   {"params", params_json(e)},
                   {"params_ci95", ci},
                   {"rmse", e.rmse},
                   {"heldout_rmse", e.heldout_rmse}};
  j["trivial"] = {{"model", r.trivial.model},
                  {"rmse", r.trivial.rmse},
                  {"heldout_rmse", r.trivial.heldout_rmse}};
  j["gain"] = r.gain;
  j["gain_vs_trivial"] = r.gain_vs_trivial;
  // a supported candidate as likely as the named one (AICc within the tie band), or null
  j["tied_with"] = r.tied_with < 0 ? nlohmann::json(nullptr)
                                   : nlohmann::json(std::string(effect_name(r.candidates[static_cast<size_t>(r.tied_with)].effect)));
  j["baseline_gain_vs_trivial"] =
      r.trivial.heldout_rmse > 0.0 ? 1.0 - r.baseline.heldout_rmse / r.trivial.heldout_rmse : 0.0;
  j["candidates"] = nlohmann::json::array();
  const double aicc_none = r.candidates.front().aicc;
  for (size_t i = 0; i < r.candidates.size(); ++i) {
    const auto& m = r.candidates[i];
    nlohmann::json bound = nlohmann::json::array();
    for (int b : m.at_bound) bound.push_back(m.specs[static_cast<size_t>(b)].name);
    j["candidates"].push_back({{"name", std::string(effect_name(m.effect))},
                               {"params", params_json(m)},
                               {"rmse", m.rmse},
                               {"heldout_rmse", m.heldout_rmse},
                               {"aicc", m.aicc},
                               {"delta_aicc", m.aicc - aicc_none},
                               {"passes_gates", m.passes_gates},
                               {"beats_trivial", m.beats_trivial},
                               {"params_at_search_bound", bound},
                               {"verdict", verdict(r, i)}});
  }
  // the error model and its fit
  {
    nlohmann::json em;
    em["name"] = r.error_model.name;
    em["correlation"] = r.error_model.correlation == Correlation::ou ? "ornstein_uhlenbeck" : "none";
    em["correlation_unit"] = r.series_unit;
    em["specimen_random_effects"] = r.specimens;
    em["specimen_offset"] = r.error_model.specimen_offset;
    em["nuisance"] = nlohmann::json::array();
    for (const auto& t : r.error_model.nuisance) {
      em["nuisance"].push_back({{"name", t.name}, {"description", t.description},
                                {"prior_sd", t.prior_sd}, {"key", t.prior_key}});
    }
    j["error_model"] = em;
  }
  for (size_t i = 0; i < r.candidates.size(); ++i) {
    const auto& m = r.candidates[i];
    nlohmann::json nz = {{"sigma", m.noise.sigma}, {"correlation_length", m.noise.ell},
                         {"white_fraction", m.noise.nugget},
                         {"specimen_rho", m.noise.rho}, {"specimen_offset_rho", m.noise.rho_offset},
                         {"n_eff", m.noise.n_eff}, {"parameters", m.noise.parameters}};
    nlohmann::json nu = nlohmann::json::object();
    for (Eigen::Index k = 0; k < m.nuisance.size(); ++k) {
      nu[m.nuisance_names[static_cast<size_t>(k)]] = m.nuisance[k];
    }
    j["candidates"][i]["noise"] = nz;
    j["candidates"][i]["nuisance"] = nu;
  }
  if (!r.detection.limits.empty()) {
    nlohmann::json d;
    d["method"] = r.detection.method;
    d["noise_rms"] = r.detection.noise_rms;
    d["rate"] = r.detection.rate;
    d["replicates"] = r.detection.replicates;
    d["seconds"] = r.detection.seconds;
    d["limits"] = nlohmann::json::array();
    for (const auto& l : r.detection.limits) {
      d["limits"].push_back({{"effect", std::string(effect_name(l.effect))},
                             {"param", l.param},
                             {"null_value", l.null_value},
                             {"direction", l.direction},
                             {"reached", l.reached},
                             {"value", l.value},
                             {"signal_rms", l.signal_rms},
                             {"ratio_to_noise", l.ratio}});
    }
    j["detection"] = d;
  }
  j["seconds"] = r.seconds;
  return j;
}

std::string diagnosis_markdown(const DiagnosisCase& c, const DiagnosisResult& r) {
  const auto& rows = c.measured.rows;
  const ModelFit& b = r.baseline;
  const ModelFit& e = r.extended();
  const EffectInfo& info = effect_info(e.effect);
  std::string md = "# Diagnosis: " + c.name + "\n\nMeasured data: `" + c.measured.source + "` (" +
                   std::to_string(rows.size()) + " measurements). Held-out rule: " +
                   c.split_rule + " (" + std::to_string(c.folds.size()) + " folds).\n\n";

  md += "## What the baseline gets wrong\n\nBaseline: " + b.model + "; ";
  for (size_t i = 0; i < b.specs.size(); ++i) {
    md += b.specs[i].name + " = " + num(b.params[static_cast<Eigen::Index>(i)]) + " ";
  }
  md += ". In-sample RMSE " + num(b.rmse) + " (" + r.rmse_unit + "), held-out RMSE " +
        num(b.heldout_rmse) + ".\n\n";
  // residual pattern per group and quantity at the first and last abscissa
  std::map<std::string, std::map<double, std::pair<double, int>>> mean_resid;
  std::map<std::string, std::map<double, double>> mean_meas;
  for (size_t i = 0; i < rows.size(); ++i) {
    const std::string key = rows[i].group + ", " + rows[i].quantity;
    auto& cell = mean_resid[key][rows[i].x];
    cell.first += rows[i].value - b.predictions[static_cast<Eigen::Index>(i)];
    cell.second += 1;
    mean_meas[key][rows[i].x] += rows[i].value;
  }
  md += "| condition, quantity | " + c.measured.x_name +
        " | mean measured | mean (measured - baseline) | relative |\n|---|---|---|---|---|\n";
  for (const auto& [key, by_x] : mean_resid) {
    for (const auto& [x, cell] : by_x) {
      const double res = cell.first / cell.second;
      const double meas = mean_meas[key][x] / cell.second;
      md += "| " + key + " | " + num(x, "%.0f") + " | " + num(meas) + " | " + num(res) + " | " +
            (meas != 0.0 ? num(100.0 * res / meas, "%+.0f %%") : std::string("-")) + " |\n";
    }
  }

  md += "\n## Named cause: " + std::string(info.name) + "\n\n" + std::string(info.physics) + "\n\n";
  if (e.effect == Effect::none) {
    md += "No candidate extension passed both gates (AICc drop and held-out improvement "
          "against the refitted baseline) with its parameters inside the searched range, so "
          "the data do not support an extension.\n\n";
    for (const auto& m : r.candidates) {
      if (m.passes_gates && !m.at_bound.empty()) {
        md += "`" + std::string(effect_name(m.effect)) + "` passed both gates but ended at a "
              "search bound (" + at_bound_text(m) + "): the data want a value outside the "
              "searched range, so the fit is not an estimate and the effect is not named.\n\n";
      }
    }
  }
  md += "## Extension\n\nModel: `" + e.model + "`.\n\n| parameter | value | 95 % CI (bootstrap) |\n"
        "|---|---|---|\n";
  for (size_t i = 0; i < e.specs.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    std::string ci = "-";
    if (e.ci_low.size()) {
      ci = "[";
      ci += num(e.ci_low[k]) + ", " + num(e.ci_high[k]) + "]";
    }
    md += "| " + e.specs[i].name + " | " + num(e.params[k]) + " | " + ci + " |\n";
  }
  if (r.quantities.size() > 1 && r.noise_model != NoiseModel::pooled) {
    md += "\nProfiled noise sd per quantity (RMS over its measurements):";
    for (size_t q = 0; q < r.quantities.size() && q < e.noise_sd.size(); ++q) {
      md += std::string(q ? "," : "") + " " + r.quantities[q] + " " + num(e.noise_sd[q]);
    }
    md += ".\n";
  }
  if (e.ci_low.size()) {
    std::vector<int> ci_at_bound = find_params_at_bound(e.specs, e.ci_low);
    for (int i : find_params_at_bound(e.specs, e.ci_high)) ci_at_bound.push_back(i);
    std::sort(ci_at_bound.begin(), ci_at_bound.end());
    ci_at_bound.erase(std::unique(ci_at_bound.begin(), ci_at_bound.end()), ci_at_bound.end());
    for (int i : ci_at_bound) {
      md += "\nThe interval of " + e.specs[static_cast<size_t>(i)].name + " reaches a search "
            "bound: the data bound it on one side only.\n";
    }
  }
  const double base_vs_trivial =
      r.trivial.heldout_rmse > 0.0 ? 1.0 - b.heldout_rmse / r.trivial.heldout_rmse : 0.0;
  md += "\nIn-sample RMSE " + num(e.rmse) + ", held-out RMSE " + num(e.heldout_rmse) +
        " (" + r.rmse_unit + ").\n\n**Gain** = 1 - heldout_rmse_extended / "
        "heldout_rmse_baseline = " + num(r.gain, "%.3f") + ".\n\n"
        "**Against the trivial predictor** (" + r.trivial.model + ", held out: from the "
        "training rows; a candidate must beat it by the held-out margin to be named): held-out RMSE " + num(r.trivial.heldout_rmse) + "; gain of the extended "
        "model 1 - " + num(e.heldout_rmse) + " / " + num(r.trivial.heldout_rmse) + " = " +
        num(r.gain_vs_trivial, "%.3f") + ", of the baseline " + num(base_vs_trivial, "%.3f") +
        (r.gain_vs_trivial <= 0.0 ? " (the extended model predicts no better than the "
                                    "measured mean)" : "") + ".\n\n";

  md += "## Candidates\n\n| effect | held-out RMSE | AICc | dAICc vs none | parameters | "
        "verdict |\n|---|---|---|---|---|---|\n";
  for (size_t ci = 0; ci < r.candidates.size(); ++ci) {
    const auto& m = r.candidates[ci];
    std::string ps;
    for (size_t i = 0; i < m.specs.size(); ++i) {
      ps += (i ? ", " : "") + m.specs[i].name + " = " + num(m.params[static_cast<Eigen::Index>(i)]);
    }
    md += "| " + std::string(effect_name(m.effect)) + " | " + num(m.heldout_rmse) + " | " +
          num(m.aicc, "%.1f") + " | " + num(m.aicc - r.candidates.front().aicc, "%.1f") + " | " +
          ps + " | " + verdict(r, ci) + " |\n";
  }
  md += "\nSelection: a candidate must lower AICc by more than the threshold and the held-out "
        "RMSE by more than the threshold fraction against `none` (the baseline refitted by "
        "least squares), with no parameter at a search bound; among those the lowest AICc wins "
        "(the likelihood of all measurements under the error model; the held-out error of a "
        "few folds is a gate, not a ranking), except that candidates within " + num(r.tie_band, "%g") +
        " of the lowest AICc are not told apart by it and the lower held-out RMSE names one of "
        "them. ";
  md += error_model_markdown(r);
  md += detection_markdown(r);
  md += "\n";
  switch (r.noise_model) {
    case NoiseModel::pooled:
      md += "Noise: one sd for all measurements, other quantities converted into " +
            r.rmse_unit + " by the ratio of measured RMS values (the residuals are model "
            "discrepancy, not measurement noise).\n";
      break;
    case NoiseModel::per_quantity:
    case NoiseModel::proportional:
      md += std::string("Noise: per measured quantity ") +
            (r.noise_model == NoiseModel::proportional ? "a sd a + b |value|"
                                                       : "one sd") +
            ", profiled in every fit; with several quantities an RMSE is the count-weighted "
            "geometric mean of the per-quantity RMSEs (the same likelihood), each converted "
            "into " + r.rmse_unit + " by the ratio of measured RMS values.\n";
      break;
  }
  return md;
}

std::string residuals_csv(const DiagnosisCase& c, const DiagnosisResult& r) {
  std::string out = "group,specimen,quantity," + c.measured.x_name +
                    ",measured,baseline,extended,heldout_baseline,heldout_extended\n";
  const auto& e = r.extended();
  for (size_t i = 0; i < c.measured.rows.size(); ++i) {
    const auto& m = c.measured.rows[i];
    const auto k = static_cast<Eigen::Index>(i);
    out += m.group + "," + m.specimen + "," + m.quantity + "," + num(m.x, "%.10g") + "," +
           num(m.value, "%.10g") + "," + num(r.baseline.predictions[k], "%.10g") + "," +
           num(e.predictions[k], "%.10g") + "," + num(r.baseline.heldout_predictions[k], "%.10g") +
           "," + num(e.heldout_predictions[k], "%.10g") + "\n";
  }
  return out;
}

std::string curves_csv(const DiagnosisCase& c, const DiagnosisResult& r) {
  std::string out = "model,group,quantity," + c.measured.x_name + ",value\n";
  if (!c.curves) return out;
  const std::pair<const char*, const ModelFit*> models[] = {{"baseline", &r.baseline},
                                                             {"extended", &r.extended()}};
  for (const auto& [name, m] : models) {
    for (const auto& p : c.curves(m->effect, baseline_of(c, *m), effect_of(c, *m))) {
      out += std::string(name) + "," + p.group + "," + p.quantity + "," + num(p.x, "%.10g") +
             "," + num(p.value, "%.10g") + "\n";
    }
  }
  return out;
}

}  // namespace kneesim::diagnosis
