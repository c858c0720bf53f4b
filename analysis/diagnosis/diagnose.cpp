#include "analysis/diagnosis/diagnose.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>

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

namespace {

// The measurements with their noise and specimen structure.
//
// Noise (DiagnosisCase::noise_model): one sd for all rows (pooled), one per measured quantity,
// or, when the measurement error grows with the measured amount (wear: a balance or
// profilometer error plus a relative part), a sd a_q + b_q |f| per quantity. Residuals (own
// units) are weighted by w_i, sd_i = sigma / w_i; w_i starts at unit_i, which converts quantity
// q into the first quantity's unit by the ratio of the measured RMS values (the conversion only
// sets the unit the RMSEs are printed in; the likelihood does not depend on it), and is
// re-estimated from the fit's residuals, or, for the proportional line with specimens, once
// from the pure error and shared by every candidate (diagnose()). Why: volume and depth (AP and IE) are measured with different
// instruments and precisions; with one pooled variance the noisier quantity is over-weighted,
// and an effect that changes only that quantity (creep: depth) gains likelihood by fitting its
// noise (about 1 clean block-on-ring set in 750 was named `creep` that way). A sd that grows
// with the value, fitted as a constant, likewise over-weights the large late measurements.
//
// Specimens: specimens of one material scatter in wear factor (multiplicatively), so the
// residuals of one specimen are correlated; when specimens are given, every model is fitted
// with a specimen random effect: y_s = f_s + u_s dg_s + e, u_s ~ N(0, tau^2), dg_s = derivative
// of the specimen's baseline curve with respect to ln k. In weighted residuals its covariance
// is sigma^2 (I + rho g g^T), g = w dg, rho = tau^2 / sigma^2, whitened exactly (rank-one
// update). Without it, AICc treats the 4-8 correlated points of a specimen as independent and
// mistakes specimen scatter between loads for a pressure effect.
struct Problem {
  const DiagnosisCase& c;
  Eigen::VectorXd y;                       // measured values
  Eigen::VectorXd unit;                    // quantity -> first quantity's unit, per row
  std::vector<int> quantity;               // quantity index per row
  std::vector<std::string> quantity_names; // first = the RMSE unit
  std::vector<std::vector<int>> clusters;  // specimens (rows), or one row each
  Eigen::VectorXd dg;                      // random-effect direction per row (unweighted)
  bool random_effect = false;              // specimens given: fit tau too
  NoiseModel noise = NoiseModel::per_quantity;  // the case's, with the row-count fallback
  Eigen::VectorXd fixed_w;                 // row weights shared by every candidate, or empty
  int quantities() const { return static_cast<int>(quantity_names.size()); }
};

// a fit's noise model: the residual weight of every row and the specimen variance ratio
struct Noise {
  Eigen::VectorXd w;  // per row [1/quantity unit, up to the common sigma]
  double rho = 0.0;   // tau^2 / sigma^2 in weighted units [-]
};

Eigen::VectorXd initial_of(const std::vector<ParamSpec>& specs, const Eigen::VectorXd& baseline) {
  Eigen::VectorXd p(static_cast<Eigen::Index>(specs.size()));
  for (size_t i = 0; i < specs.size(); ++i) {
    p[static_cast<Eigen::Index>(i)] =
        (i < static_cast<size_t>(baseline.size())) ? baseline[static_cast<Eigen::Index>(i)]
                                                    : specs[i].initial;
  }
  return p;
}

Eigen::VectorXd predict(const Problem& pb, Effect e, const Eigen::VectorXd& params,
                        const std::vector<int>& rows) {
  const Eigen::Index nb = static_cast<Eigen::Index>(pb.c.baseline_params.size());
  return pb.c.predict(e, params.head(nb), params.tail(params.size() - nb), rows);
}

std::vector<int> flatten(const std::vector<std::vector<int>>& clusters) {
  std::vector<int> rows;
  for (const auto& cl : clusters) rows.insert(rows.end(), cl.begin(), cl.end());
  return rows;
}

// whitened residuals of `clusters` (rows may repeat across clusters: bootstrap draws) with
// row weights w and variance ratio rho, for measured values y
Eigen::VectorXd whitened(const Problem& pb, const Eigen::VectorXd& y, Effect e,
                         const Eigen::VectorXd& params,
                         const std::vector<std::vector<int>>& clusters, double rho,
                         const Eigen::VectorXd& w) {
  const auto rows = flatten(clusters);
  Eigen::VectorXd r = predict(pb, e, params, rows);
  for (size_t i = 0; i < rows.size(); ++i) {
    r[static_cast<Eigen::Index>(i)] = (r[static_cast<Eigen::Index>(i)] - y[rows[i]]) * w[rows[i]];
  }
  if (rho <= 0.0) return r;
  Eigen::Index at = 0;
  for (const auto& cl : clusters) {
    const auto n = static_cast<Eigen::Index>(cl.size());
    Eigen::VectorXd gs(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const int row = cl[static_cast<size_t>(i)];
      gs[i] = pb.dg[row] * w[row];
    }
    const double g2 = gs.squaredNorm();
    if (g2 > 0.0) {
      const double c = 1.0 - 1.0 / std::sqrt(1.0 + rho * g2);
      const Eigen::VectorXd gh = gs / std::sqrt(g2);
      auto seg = r.segment(at, n);
      seg -= c * gh.dot(seg) * gh;
    }
    at += n;
  }
  return r;
}

double cluster_g2(const Problem& pb, const std::vector<int>& cl, const Eigen::VectorXd& w) {
  double g2 = 0.0;
  for (int i : cl) g2 += pb.dg[i] * w[i] * pb.dg[i] * w[i];
  return g2;
}

double log_det(const Problem& pb, const std::vector<std::vector<int>>& clusters, double rho,
               const Eigen::VectorXd& w) {
  double ld = 0.0;
  for (const auto& cl : clusters) ld += std::log1p(rho * cluster_g2(pb, cl, w));
  return ld;
}

FitResult fit_clusters(const Problem& pb, const Eigen::VectorXd& y, Effect e,
                       const std::vector<ParamSpec>& specs, const Eigen::VectorXd& start,
                       const std::vector<std::vector<int>>& clusters, const Noise& noise,
                       bool multi) {
  auto residuals = [&](const Eigen::VectorXd& p) {
    return whitened(pb, y, e, p, clusters, noise.rho, noise.w);
  };
  return fit_least_squares(residuals, specs, start, multi, pb.c.fit_control);
}

// clusters restricted to `rows`
std::vector<std::vector<int>> clusters_of(const Problem& pb, const std::vector<int>& rows) {
  std::vector<char> in(static_cast<size_t>(pb.y.size()), 0);
  for (int i : rows) in[static_cast<size_t>(i)] = 1;
  std::vector<std::vector<int>> out;
  for (const auto& cl : pb.clusters) {
    std::vector<int> kept;
    for (int i : cl) {
      if (in[static_cast<size_t>(i)]) kept.push_back(i);
    }
    if (!kept.empty()) out.push_back(std::move(kept));
  }
  return out;
}

// One number for a model's errors (pooled noise: the RMS of the converted residuals; otherwise
// as follows): the count-weighted geometric mean of the per-quantity RMSEs,
// each in the first quantity's unit. It is the Gaussian likelihood with one variance per
// quantity, profiled (-2 log L / n = sum_q (n_q / n) ln RMSE_q^2 + const), the noise model of
// the fits; so ratios between models (the gain, the held-out threshold) do not depend on the
// unit conversion, and a quantity with a larger spread does not dominate. For one quantity it
// is the plain RMSE.
double score(const Problem& pb, const Eigen::VectorXd& pred) {
  if (pb.noise == NoiseModel::pooled) {  // one sd: the RMSE of the converted residuals
    return std::sqrt((pred - pb.y).cwiseProduct(pb.unit).squaredNorm() /
                     static_cast<double>(pred.size()));
  }
  std::vector<double> ss(static_cast<size_t>(pb.quantities()), 0.0);
  std::vector<double> count(ss.size(), 0.0);
  for (Eigen::Index i = 0; i < pred.size(); ++i) {
    const size_t q = static_cast<size_t>(pb.quantity[static_cast<size_t>(i)]);
    const double d = (pred[i] - pb.y[i]) * pb.unit[i];
    ss[q] += d * d;
    count[q] += 1.0;
  }
  double log_sum = 0.0, n = 0.0;
  for (size_t q = 0; q < ss.size(); ++q) {
    if (count[q] == 0.0) continue;
    log_sum += 0.5 * count[q] * std::log(std::max(ss[q] / count[q], 1e-300));
    n += count[q];
  }
  return std::exp(log_sum / n);
}

std::vector<int> all_rows(size_t n) {
  std::vector<int> rows(n);
  for (size_t i = 0; i < n; ++i) rows[i] = static_cast<int>(i);
  return rows;
}

// -2 log L (profiled over sigma) plus the AICc penalty; log_w_sum = sum over rows of
// ln(w_i / unit_i) (the Jacobian of the row scaling, without the constant unit conversion);
// k counts the noise parameters and tau too
double aicc(double rss_white, double log_det_sum, double log_w_sum, int n, int k) {
  return n * std::log(std::max(rss_white, 1e-300) / n) + log_det_sum - 2.0 * log_w_sum +
         2.0 * k + 2.0 * k * (k + 1.0) / (n - k - 1.0);
}

double log_w_sum(const Problem& pb, const Eigen::VectorXd& w) {
  double s = 0.0;
  for (Eigen::Index i = 0; i < w.size(); ++i) s += std::log(w[i] / pb.unit[i]);
  return s;
}

// variance ratios tried for the specimen random effect, relative to the mean |g_s|^2
constexpr double kRhoGrid[] = {0.0,  0.05, 0.1,   0.2,   0.5,   1.0,   2.0,    5.0,   10.0,
                               20.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0, 5000.0};

// golden-section steps refining the specimen variance ratio after the grid (ln rho to within
// about 0.03)
constexpr int kRhoRefinements = 8;

// alternations between the fit and the noise model (converged when no weight moves by more
// than 1 %; two or three suffice in the tests)
constexpr int kNoiseIterations = 5;

// fewest measurements of a quantity for which a proportional noise line is fitted
constexpr int kMinRowsProportional = 20;

// noise parameters per quantity: sigma_q, or a_q and b_q
int noise_params(const Problem& pb) {
  switch (pb.noise) {
    case NoiseModel::pooled: return 1;
    case NoiseModel::per_quantity: return pb.quantities();
    case NoiseModel::proportional: return 2 * pb.quantities();
  }
  return pb.quantities();
}

// row weights from the residuals of a fit, with each specimen's random effect (its best linear
// unbiased prediction) removed: per quantity the RMS residual, or, with proportional noise,
// the least-squares line |e| = a + b |f| (a >= 2 % of the sd at the mean |f|, so a zero
// prediction does not get an infinite weight); all in the first quantity's unit
Eigen::VectorXd noise_weights(const Problem& pb, const Eigen::VectorXd& pred, const Noise& noise) {
  Eigen::VectorXd resid = pb.y - pred;
  if (noise.rho > 0.0) {
    for (const auto& cl : pb.clusters) {
      double gz = 0.0;
      for (int i : cl) gz += pb.dg[i] * noise.w[i] * resid[i] * noise.w[i];
      const double u = noise.rho * gz / (1.0 + noise.rho * cluster_g2(pb, cl, noise.w));
      for (int i : cl) resid[i] -= u * pb.dg[i];
    }
  }
  const Eigen::Index n = resid.size();
  Eigen::VectorXd sd(n);
  for (int q = 0; q < pb.quantities(); ++q) {
    double s1 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (pb.quantity[static_cast<size_t>(i)] != q) continue;
      const double x = std::abs(pred[i]) * pb.unit[i], y = std::abs(resid[i]) * pb.unit[i];
      s1 += 1, sx += x, sy += y, sxx += x * x, sxy += x * y, syy += y * y;
    }
    double a = std::sqrt(syy / std::max(s1, 1.0)), b = 0.0;  // homoscedastic: the RMS
    if (pb.noise == NoiseModel::proportional) {
      const double det = s1 * sxx - sx * sx;
      b = det > 0.0 ? (s1 * sxy - sx * sy) / det : 0.0;
      a = (sy - b * sx) / s1;
      if (b < 0.0) b = 0.0, a = sy / s1;
      if (a < 0.0) a = 0.0, b = sxy / std::max(sxx, 1e-300);
      a = std::max(a, 0.02 * (a + b * sx / s1));
    }
    for (Eigen::Index i = 0; i < n; ++i) {
      if (pb.quantity[static_cast<size_t>(i)] != q) continue;
      sd[i] = std::max(a + b * std::abs(pred[i]) * pb.unit[i], 1e-300);
    }
  }
  // scale: the first quantity's mean weight equals its unit conversion (1)
  Eigen::VectorXd w = sd.cwiseInverse();
  double mean0 = 0.0, count0 = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (pb.quantity[static_cast<size_t>(i)] == 0) mean0 += w[i], count0 += 1.0;
  }
  w *= count0 / mean0;
  return w.cwiseProduct(pb.unit).eval();
}

ModelFit fit_candidate(const Problem& pb, Effect e, const Eigen::VectorXd& calibrated,
                       const DiagnosisOptions& opt, Noise* noise_out) {
  const DiagnosisCase& c = pb.c;
  ModelFit m;
  m.effect = e;
  m.specs = c.baseline_params;
  const auto eff = case_effect_params(c, e);
  m.specs.insert(m.specs.end(), eff.begin(), eff.end());
  m.model = std::string(effect_info(e).extension);
  if (const auto it = c.model_notes.find(e); it != c.model_notes.end()) {
    m.model += "; " + it->second;
  }
  const auto rows = all_rows(c.measured.rows.size());
  const int n = static_cast<int>(rows.size());
  const int k = static_cast<int>(m.specs.size()) + noise_params(pb) + (pb.random_effect ? 1 : 0);
  if (n - k - 1 <= 0) {
    throw InputError(c.measured.source + ": rows " + std::to_string(c.measured.rows.front().row) +
                     "-" + std::to_string(c.measured.rows.back().row) + ", column " +
                     c.measured.rows.front().quantity + ": " + std::to_string(n) +
                     " measurements are fewer than the " + std::to_string(k + 2) +
                     " needed to fit the " + std::to_string(m.specs.size()) +
                     " parameters of candidate " + std::string(effect_name(e)) + ".");
  }
  // alternate: fit at the current row weights (multi-start at rho = 0 the first time, then
  // profile the specimen variance ratio), re-estimate the weights from the residuals (not
  // with pooled or shared weights); keep the (params, noise) with the lowest AICc, an exact
  // likelihood value at each step
  Noise noise{pb.fixed_w.size() ? pb.fixed_w : pb.unit, 0.0};
  Noise best_noise = noise;
  FitResult best;
  m.aicc = std::numeric_limits<double>::infinity();
  Eigen::VectorXd start = initial_of(m.specs, calibrated);
  for (int it = 0; it < kNoiseIterations; ++it) {
    const Eigen::VectorXd& w = noise.w;
    const double log_w = log_w_sum(pb, w);
    Noise at{w, 0.0};
    FitResult fit = fit_clusters(pb, pb.y, e, m.specs, start, pb.clusters, at,
                                 (opt.multi_start || c.multi_start_effects.count(e)) && it == 0);
    double fit_aicc = aicc(fit.rss, 0.0, log_w, n, k);
    double fit_rho = 0.0;
    if (pb.random_effect) {
      double g2_mean = 0.0;
      for (const auto& cl : pb.clusters) {
        g2_mean += cluster_g2(pb, cl, w) / static_cast<double>(pb.clusters.size());
      }
      Eigen::VectorXd warm = fit.params;
      auto try_rho = [&](double rho) {
        at.rho = rho;
        const FitResult fr = fit_clusters(pb, pb.y, e, m.specs, warm, pb.clusters, at, false);
        const double a = aicc(fr.rss, log_det(pb, pb.clusters, at.rho, w), log_w, n, k);
        warm = fr.params;
        if (a < fit_aicc) {
          fit_aicc = a;
          fit = fr;
          fit_rho = at.rho;
        }
        return a;
      };
      for (double s : kRhoGrid) {
        if (s > 0.0) try_rho(s / g2_mean);
      }
      // refine ln rho by golden section between the best grid point's neighbours: a grid
      // step of 2-2.5x leaves up to about n_specimens/8 of -2 log L on the table, at random
      // for each candidate, which would add noise to dAICc
      if (fit_rho > 0.0) {
        double lo = std::log(fit_rho / 2.5), hi = std::log(fit_rho * 2.5);
        const double r = 0.5 * (std::sqrt(5.0) - 1.0);
        double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
        double f1 = try_rho(std::exp(x1)), f2 = try_rho(std::exp(x2));
        for (int it = 0; it < kRhoRefinements; ++it) {
          if (f1 < f2) {
            hi = x2, x2 = x1, f2 = f1, x1 = hi - r * (hi - lo), f1 = try_rho(std::exp(x1));
          } else {
            lo = x1, x1 = x2, f1 = f2, x2 = lo + r * (hi - lo), f2 = try_rho(std::exp(x2));
          }
        }
      }
    }
    noise.rho = fit_rho;
    if (fit_aicc < m.aicc) {
      m.aicc = fit_aicc;
      best = fit;
      best_noise = noise;
    }
    if (pb.noise == NoiseModel::pooled || pb.fixed_w.size() > 0 ||
        (pb.quantities() == 1 && pb.noise == NoiseModel::per_quantity)) {
      break;
    }
    const Eigen::VectorXd w_new = noise_weights(pb, predict(pb, e, fit.params, rows), noise);
    const double moved = (w_new.array().log() - noise.w.array().log()).abs().maxCoeff();
    noise.w = w_new;
    start = fit.params;
    if (moved < 0.01) break;
  }
  // no step had a finite likelihood (predictions or weights not finite): numerical trouble,
  // reported as such rather than evaluated further
  if (best.params.size() != static_cast<Eigen::Index>(m.specs.size())) {
    throw std::runtime_error("the fit of candidate " + std::string(effect_name(e)) + " to " +
                             c.measured.source + " found no parameters with a finite "
                             "likelihood; the measurements cannot be modelled by it");
  }
  *noise_out = best_noise;
  m.params = best.params;
  m.predictions = predict(pb, e, m.params, rows);
  m.rss = (m.predictions - pb.y).cwiseProduct(pb.unit).squaredNorm();
  m.rmse = score(pb, m.predictions);
  {
    // profiled noise sd per quantity, in the quantity's own unit
    // (the RMS over each quantity's rows of the modelled sd)
    const double sigma = std::sqrt(best.rss / n);
    m.noise_sd.assign(static_cast<size_t>(pb.quantities()), 0.0);
    std::vector<double> count(m.noise_sd.size(), 0.0);
    for (Eigen::Index i = 0; i < pb.y.size(); ++i) {
      const size_t q = static_cast<size_t>(pb.quantity[static_cast<size_t>(i)]);
      m.noise_sd[q] += std::pow(sigma / best_noise.w[i], 2);
      count[q] += 1.0;
    }
    for (size_t q = 0; q < count.size(); ++q) m.noise_sd[q] = std::sqrt(m.noise_sd[q] / count[q]);
  }
  // held-out: refit on each fold's training rows, warm-started at the full-data optimum, with
  // the full-data noise model
  m.heldout_predictions = Eigen::VectorXd::Constant(n, NAN);
  for (const Fold& f : c.folds) {
    const FitResult fr =
        fit_clusters(pb, pb.y, e, m.specs, m.params, clusters_of(pb, f.train), best_noise, false);
    const Eigen::VectorXd p = predict(pb, e, fr.params, f.test);
    for (size_t i = 0; i < f.test.size(); ++i) m.heldout_predictions[f.test[i]] = p[static_cast<Eigen::Index>(i)];
  }
  m.heldout_rmse = score(pb, m.heldout_predictions);
  return m;
}

ModelFit practitioner_baseline(const Problem& pb) {
  const DiagnosisCase& c = pb.c;
  ModelFit m;
  m.effect = Effect::none;
  m.model = c.baseline_model;
  m.specs = c.baseline_params;
  const auto rows = all_rows(c.measured.rows.size());
  m.params = c.calibrate_baseline(rows);
  const Eigen::VectorXd none;
  m.predictions = c.predict(Effect::none, m.params, none, rows);
  m.rss = (m.predictions - pb.y).cwiseProduct(pb.unit).squaredNorm();
  m.rmse = score(pb, m.predictions);
  m.aicc = aicc(m.rss, 0.0, 0.0, static_cast<int>(rows.size()),
                static_cast<int>(m.specs.size()) + 1);
  m.heldout_predictions = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(rows.size()), NAN);
  for (const Fold& f : c.folds) {
    const Eigen::VectorXd p = c.predict(Effect::none, c.calibrate_baseline(f.train), none, f.test);
    for (size_t i = 0; i < f.test.size(); ++i) m.heldout_predictions[f.test[i]] = p[static_cast<Eigen::Index>(i)];
  }
  m.heldout_rmse = score(pb, m.heldout_predictions);
  return m;
}

// the trivial predictor: each quantity's measured mean (held out: over the fold's training
// rows), or the case's own (DiagnosisCase::trivial_predict); no parameters are fitted, so it
// has no AICc
ModelFit trivial_predictor(const Problem& pb) {
  const DiagnosisCase& c = pb.c;
  const auto n = static_cast<Eigen::Index>(c.measured.rows.size());
  auto means = [&](const std::vector<int>& rows) {
    std::vector<double> sum(static_cast<size_t>(pb.quantities()), 0.0), count(sum.size(), 0.0);
    for (int i : rows) {
      sum[static_cast<size_t>(pb.quantity[static_cast<size_t>(i)])] += pb.y[i];
      count[static_cast<size_t>(pb.quantity[static_cast<size_t>(i)])] += 1.0;
    }
    for (size_t q = 0; q < sum.size(); ++q) sum[q] = count[q] > 0.0 ? sum[q] / count[q] : 0.0;
    return sum;
  };
  auto predict = [&](const std::vector<int>& train, const std::vector<int>& rows) {
    if (c.trivial_predict) return c.trivial_predict(train, rows);
    const auto mean = means(train);
    Eigen::VectorXd p(static_cast<Eigen::Index>(rows.size()));
    for (size_t k = 0; k < rows.size(); ++k) {
      p[static_cast<Eigen::Index>(k)] = mean[static_cast<size_t>(pb.quantity[static_cast<size_t>(rows[k])])];
    }
    return p;
  };
  ModelFit m;
  m.effect = Effect::none;
  m.model = c.trivial_predict ? c.trivial_model : "the measured mean of each quantity (no model)";
  m.aicc = NAN;
  const std::vector<int> all = all_rows(static_cast<size_t>(n));
  m.predictions = predict(all, all);
  m.rss = (m.predictions - pb.y).cwiseProduct(pb.unit).squaredNorm();
  m.rmse = score(pb, m.predictions);
  m.heldout_predictions = Eigen::VectorXd::Constant(n, NAN);
  for (const Fold& f : c.folds) {
    const Eigen::VectorXd p = predict(f.train, f.test);
    for (size_t k = 0; k < f.test.size(); ++k) m.heldout_predictions[f.test[k]] = p[static_cast<Eigen::Index>(k)];
  }
  m.heldout_rmse = score(pb, m.heldout_predictions);
  return m;
}

// bootstrap of the chosen fit: specimens resampled within each condition when specimens are
// given (their scatter dominates), otherwise residuals resampled within each quantity
void bootstrap(const Problem& pb, ModelFit& m, const Noise& noise, const DiagnosisOptions& opt) {
  if (opt.bootstrap <= 0) return;
  const auto& rows = pb.c.measured.rows;
  std::mt19937_64 rng(opt.seed);
  const Eigen::Index np = m.params.size();
  std::vector<std::vector<double>> samples(static_cast<size_t>(np));
  std::map<std::string, std::vector<int>> by_key;  // quantity -> rows, or group -> clusters
  if (pb.random_effect) {
    for (size_t i = 0; i < pb.clusters.size(); ++i) {
      by_key[rows[static_cast<size_t>(pb.clusters[i].front())].group].push_back(static_cast<int>(i));
    }
  } else {
    for (size_t i = 0; i < rows.size(); ++i) by_key[rows[i].quantity].push_back(static_cast<int>(i));
  }
  const Eigen::VectorXd resid = pb.y - m.predictions;
  for (int b = 0; b < opt.bootstrap; ++b) {
    FitResult fr;
    if (pb.random_effect) {
      std::vector<std::vector<int>> draw;
      for (const auto& [g, members] : by_key) {
        std::uniform_int_distribution<size_t> pick(0, members.size() - 1);
        for (size_t j = 0; j < members.size(); ++j) {
          draw.push_back(pb.clusters[static_cast<size_t>(members[pick(rng)])]);
        }
      }
      fr = fit_clusters(pb, pb.y, m.effect, m.specs, m.params, draw, noise, false);
    } else {
      Eigen::VectorXd y_star = m.predictions;
      for (const auto& [q, members] : by_key) {
        std::uniform_int_distribution<size_t> pick(0, members.size() - 1);
        for (int i : members) y_star[i] += resid[members[pick(rng)]];
      }
      fr = fit_clusters(pb, y_star, m.effect, m.specs, m.params, pb.clusters, noise, false);
    }
    for (Eigen::Index j = 0; j < np; ++j) samples[static_cast<size_t>(j)].push_back(fr.params[j]);
  }
  m.ci_low.resize(np);
  m.ci_high.resize(np);
  for (Eigen::Index j = 0; j < np; ++j) {
    auto& s = samples[static_cast<size_t>(j)];
    std::sort(s.begin(), s.end());
    auto quantile = [&s](double q) {
      const double pos = q * static_cast<double>(s.size() - 1);
      const size_t lo = static_cast<size_t>(pos);
      const size_t hi = std::min(lo + 1, s.size() - 1);
      return s[lo] + (pos - static_cast<double>(lo)) * (s[hi] - s[lo]);
    };
    m.ci_low[j] = quantile(0.025);
    m.ci_high[j] = quantile(0.975);
  }
}

}  // namespace

DiagnosisResult diagnose(const DiagnosisCase& c, const DiagnosisOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto& rows = c.measured.rows;
  if (rows.empty()) throw InputError(c.measured.source + ": row 2: the file holds no measurements.");
  DiagnosisResult res;
  // quantities in order of appearance; unit conversion into the first one by RMS magnitudes
  std::map<std::string, double> sum_sq;
  std::map<std::string, int> count;
  std::map<std::string, int> index;
  Problem pb{c, Eigen::VectorXd(static_cast<Eigen::Index>(rows.size())),
             Eigen::VectorXd(static_cast<Eigen::Index>(rows.size())), {}, {}, {}, {}, false};
  for (const auto& r : rows) {
    sum_sq[r.quantity] += r.value * r.value;
    count[r.quantity] += 1;
    if (!index.count(r.quantity)) {
      index[r.quantity] = static_cast<int>(pb.quantity_names.size());
      pb.quantity_names.push_back(r.quantity);
    }
  }
  res.rmse_unit = rows.front().quantity;
  res.quantities = pb.quantity_names;
  const double ref = std::sqrt(sum_sq[res.rmse_unit] / count[res.rmse_unit]);
  for (size_t i = 0; i < rows.size(); ++i) {
    const double scale = std::sqrt(sum_sq[rows[i].quantity] / count[rows[i].quantity]);
    pb.y[static_cast<Eigen::Index>(i)] = rows[i].value;
    pb.unit[static_cast<Eigen::Index>(i)] = (scale > 0.0) ? ref / scale : 1.0;
    pb.quantity.push_back(index[rows[i].quantity]);
  }
  res.weights = pb.unit;
  // a noise line a + b |f| needs enough residuals per quantity; with fewer, one sd each
  pb.noise = c.noise_model;
  for (const auto& [q, n] : count) {
    if (pb.noise == NoiseModel::proportional && n < kMinRowsProportional) {
      pb.noise = NoiseModel::per_quantity;
    }
  }
  res.noise_model = pb.noise;

  // specimens: clusters of rows; without them every row is its own cluster
  std::map<std::string, std::vector<int>> by_specimen;
  bool specimens = true;
  for (size_t i = 0; i < rows.size(); ++i) {
    specimens = specimens && !rows[i].specimen.empty();
    by_specimen[rows[i].group + "/" + rows[i].specimen].push_back(static_cast<int>(i));
  }
  pb.random_effect = specimens && by_specimen.size() >= 4;
  if (pb.random_effect) {
    for (auto& [key, members] : by_specimen) pb.clusters.push_back(std::move(members));
  } else {
    for (size_t i = 0; i < rows.size(); ++i) pb.clusters.push_back({static_cast<int>(i)});
  }

  res.baseline = practitioner_baseline(pb);
  res.trivial = trivial_predictor(pb);
  // random-effect direction: d prediction / d ln(specimen parameter) (for depth this is not
  // the depth itself: depth grows less than proportionally with volume)
  // (a case without baseline parameters, e.g. forces, has no specimen direction)
  pb.dg = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(rows.size()));
  if (c.specimen_param < static_cast<int>(c.baseline_params.size())) {
    Eigen::VectorXd b2 = res.baseline.params;
    b2[c.specimen_param] *= 1.01;
    const Eigen::VectorXd none;
    const Eigen::VectorXd up = c.predict(Effect::none, b2, none, all_rows(rows.size()));
    pb.dg = (up - res.baseline.predictions) / std::log(1.01);
  }
  // proportional noise with specimens: the noise line of each quantity is a property of the
  // measurement, so it is estimated once, from the pure error (each specimen's measurements
  // about its own scaled baseline curve, which absorbs any level difference between specimens
  // and conditions), and shared by every candidate; only the common sigma is profiled per
  // candidate. Estimated per candidate from its own residuals instead, the line differed
  // between candidates and added up to 5 to a clean data set's dAICc.
  if (pb.noise == NoiseModel::proportional && pb.random_effect) {
    Eigen::VectorXd own = res.baseline.predictions;
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
    pb.fixed_w = noise_weights(pb, own, Noise{pb.unit, 0.0});
  }
  std::vector<Effect> effects = {Effect::none};
  effects.insert(effects.end(), c.candidates.begin(), c.candidates.end());
  std::vector<Noise> noises;
  for (Effect e : effects) {
    Noise noise;
    res.candidates.push_back(fit_candidate(pb, e, res.baseline.params, options, &noise));
    noises.push_back(noise);
  }

  // selection against "none"
  const ModelFit& none = res.candidates.front();
  res.selected = 0;
  for (auto& m : res.candidates) m.at_bound = find_params_at_bound(m.specs, m.params);
  for (size_t i = 1; i < res.candidates.size(); ++i) {
    ModelFit& m = res.candidates[i];
    const bool ic_ok = m.aicc < none.aicc - options.ic_threshold;
    const bool heldout_ok = m.heldout_rmse < (1.0 - options.heldout_threshold) * none.heldout_rmse;
    // a gain the trivial predictor also achieves is not a finding: the same held-out margin
    // against it (binds only where the baseline predicts worse than the trivial predictor)
    m.beats_trivial = !options.trivial_gate ||
                      m.heldout_rmse < (1.0 - options.heldout_threshold) * res.trivial.heldout_rmse;
    m.passes_gates = ic_ok && heldout_ok;
    if (m.passes_gates && m.beats_trivial && m.at_bound.empty() &&
        (res.selected == 0 || m.heldout_rmse < res.extended().heldout_rmse)) {
      res.selected = static_cast<int>(i);
    }
  }
  bootstrap(pb, res.candidates[static_cast<size_t>(res.selected)],
            noises[static_cast<size_t>(res.selected)], options);
  res.gain = (res.baseline.heldout_rmse > 0.0)
                 ? 1.0 - res.extended().heldout_rmse / res.baseline.heldout_rmse
                 : 0.0;
  res.gain_vs_trivial = (res.trivial.heldout_rmse > 0.0)
                            ? 1.0 - res.extended().heldout_rmse / res.trivial.heldout_rmse
                            : 0.0;
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace kneesim::diagnosis
