// The candidate fits of the diagnosis (diagnosis_problem.h): a candidate's parameters and
// its error model profiled together (specimen variance ratios, correlation length, white
// fraction, noise weights; grid then golden section in ln of each), the practitioner's
// baseline, the trivial predictor and the bootstrap. The problem, the error model's whitening,
// the likelihood and the held-out predictions they use live in diagnosis_problem.cpp.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>

#include "analysis/diagnosis/diagnosis_problem.h"
#include "engine/errors.h"

namespace kneesim::diagnosis::detail {
namespace {

// variance ratios tried for the specimen random effect, relative to the mean |g_s|^2
constexpr double kRhoGrid[] = {0.0,  0.05, 0.1,   0.2,   0.5,   1.0,   2.0,    5.0,   10.0,
                               20.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0, 5000.0};
// variance ratios tried for the specimen offset, relative to the mean |h_s|^2
constexpr double kOffsetGrid[] = {0.0, 0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0};
// correlation lengths tried, as fractions of the searched range in ln ell (plus 0: white)
constexpr int kEllGrid = 9;
// white fractions of a correlated series' variance tried (then refined in ln, below 1)
constexpr double kNuggetGrid[] = {0.0, 0.02, 0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 0.9};

// golden-section steps refining a variance ratio or a correlation length after its grid (ln
// of the value to within about 0.03)
constexpr int kRefinements = 8;

Eigen::VectorXd initial_of(const std::vector<ParamSpec>& specs, const Eigen::VectorXd& baseline) {
  Eigen::VectorXd p(static_cast<Eigen::Index>(specs.size()));
  for (size_t i = 0; i < specs.size(); ++i) {
    p[static_cast<Eigen::Index>(i)] =
        (i < static_cast<size_t>(baseline.size())) ? baseline[static_cast<Eigen::Index>(i)]
                                                    : specs[i].initial;
  }
  return p;
}

double cluster_g2(const Problem& pb, const std::vector<int>& cl, const Eigen::VectorXd& w) {
  double g2 = 0.0;
  for (int i : cl) g2 += pb.dg[i] * w[i] * pb.dg[i] * w[i];
  return g2;
}

double cluster_h2(const Problem& pb, const std::vector<int>& cl, const Eigen::VectorXd& w) {
  double h2 = 0.0;
  for (int i : cl) {
    if (pb.offset_rows[static_cast<size_t>(i)]) h2 += w[i] * w[i];
  }
  return h2;
}

// Minimises f over ln v: the grid (0 allowed as its first value), then golden section between
// the best grid value's neighbours. Returns the best value; `best_f` its objective.
double profile(const std::function<double(double)>& f, const std::vector<double>& grid,
               double* best_f) {
  double best_v = grid.front(), best = std::numeric_limits<double>::infinity();
  size_t best_i = 0;
  for (size_t i = 0; i < grid.size(); ++i) {
    const double v = f(grid[i]);
    if (v < best) best = v, best_v = grid[i], best_i = i;
  }
  if (best_v > 0.0) {
    const double below = best_i > 0 && grid[best_i - 1] > 0.0 ? grid[best_i - 1] : best_v / 2.5;
    const double above = best_i + 1 < grid.size() ? grid[best_i + 1] : best_v * 2.5;
    double lo = std::log(below), hi = std::log(above);
    const double r = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
    double f1 = f(std::exp(x1)), f2 = f(std::exp(x2));
    for (int it = 0; it < kRefinements; ++it) {
      if (f1 < f2) {
        hi = x2, x2 = x1, f2 = f1, x1 = hi - r * (hi - lo), f1 = f(std::exp(x1));
      } else {
        lo = x1, x1 = x2, f1 = f2, x2 = lo + r * (hi - lo), f2 = f(std::exp(x2));
      }
    }
    const double v = f1 < f2 ? std::exp(x1) : std::exp(x2);
    const double fv = std::min(f1, f2);
    if (fv < best) best = fv, best_v = v;
  }
  if (best_f) *best_f = best;
  return best_v;
}

// row weights from the residuals of a fit, with each specimen's random effect (its best linear
// unbiased prediction) removed: per quantity the RMS residual, or, with proportional noise,
// the least-squares line |e| = a + b |f| (a >= 2 % of the sd at the mean |f|, so a zero
// prediction does not get an infinite weight); all in the first quantity's unit
Eigen::VectorXd noise_weights(const Problem& pb, const Eigen::VectorXd& y,
                              const Eigen::VectorXd& pred, const Noise& noise) {
  Eigen::VectorXd resid = y - pred;
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
      const double x = std::abs(pred[i]) * pb.unit[i], yv = std::abs(resid[i]) * pb.unit[i];
      s1 += 1, sx += x, sy += yv, sxx += x * x, sxy += x * yv, syy += yv * yv;
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

double relative_move(double a, double b) {
  if (a == b) return 0.0;
  if (a <= 0.0 || b <= 0.0) return 1.0;
  return std::abs(std::log(a / b));
}

// fills the outputs of a fitted model: its predictions at every row in row order
// (`pred_rows`, without nuisance), the nuisance terms `beta` and the whitened rss
void finish_fit(const Problem& pb, const Eigen::VectorXd& y, ModelFit& m,
                const Eigen::VectorXd& pred_rows, const Eigen::VectorXd& beta, double rss_white,
                const Noise& noise) {
  const auto rows = all_rows(static_cast<size_t>(y.size()));
  m.nuisance = beta;
  m.nuisance_names.clear();
  for (const auto& t : pb.em.nuisance) m.nuisance_names.push_back(t.name);
  m.nuisance_contribution = Eigen::VectorXd::Zero(y.size());
  if (beta.size() > 0 && pred_rows.allFinite()) {
    m.nuisance_contribution = nuisance_columns(pb, rows, pred_rows) * beta;
  }
  m.predictions = pred_rows + m.nuisance_contribution;
  m.rss = (m.predictions - y).cwiseProduct(pb.unit).squaredNorm();
  m.rmse = score(pb, y, m.predictions);
  const double n = static_cast<double>(y.size());
  const double sigma = std::sqrt(rss_white / n);
  m.noise.sigma = sigma;
  m.noise.ell = noise.ell;
  m.noise.nugget = noise.nugget;
  m.noise.rho = noise.rho;
  m.noise.rho_offset = noise.rho_offset;
  m.noise.n_eff = effective_n(pb, noise);
  m.noise.parameters = error_parameters(pb);
  // profiled noise sd per quantity, in the quantity's own unit (the RMS over each quantity's
  // rows of the modelled sd, without the random effects and the correlation)
  m.noise_sd.assign(static_cast<size_t>(pb.quantities()), 0.0);
  std::vector<double> count(m.noise_sd.size(), 0.0);
  for (Eigen::Index i = 0; i < y.size(); ++i) {
    const size_t q = static_cast<size_t>(pb.quantity[static_cast<size_t>(i)]);
    m.noise_sd[q] += std::pow(sigma / noise.w[i], 2);
    count[q] += 1.0;
  }
  for (size_t q = 0; q < count.size(); ++q) m.noise_sd[q] = std::sqrt(m.noise_sd[q] / count[q]);
}

// a vector over the flattened rows of the full clusters, in row order
Eigen::VectorXd in_row_order(const std::vector<int>& flat, const Eigen::VectorXd& v) {
  Eigen::VectorXd out(v.size());
  for (size_t i = 0; i < flat.size(); ++i) out[flat[i]] = v[static_cast<Eigen::Index>(i)];
  return out;
}

}  // namespace

Eigen::VectorXd proportional_weights(const Problem& pb, const Eigen::VectorXd& pred) {
  return noise_weights(pb, pb.y, pred, Noise{pb.unit, 0.0, 0.0, 0.0, 0.0});
}

ModelFit fit_candidate(const Problem& pb, const Eigen::VectorXd& y, Effect e,
                       const Eigen::VectorXd& calibrated, const DiagnosisOptions& opt,
                       Noise* noise_out) {
  const DiagnosisCase& c = pb.c;
  ModelFit m;
  m.effect = e;
  m.specs = candidate_specs(pb, e);
  m.model = std::string(effect_info(e).extension);
  if (const auto it = c.model_notes.find(e); it != c.model_notes.end()) {
    m.model += "; " + it->second;
  }
  const auto rows = all_rows(static_cast<size_t>(y.size()));
  const auto flat = flatten(pb.clusters);
  const int n = static_cast<int>(rows.size());
  const int k = static_cast<int>(m.specs.size()) + error_parameters(pb);
  if (n - k - 1 <= 0) {
    throw InputError(c.measured.source + ": rows " + std::to_string(c.measured.rows.front().row) +
                     "-" + std::to_string(c.measured.rows.back().row) + ", column " +
                     c.measured.rows.front().quantity + ": " + std::to_string(n) +
                     " measurements are fewer than the " + std::to_string(k + 2) +
                     " needed to fit the " + std::to_string(m.specs.size()) +
                     " parameters of candidate " + std::string(effect_name(e)) + " with the " +
                     std::to_string(error_parameters(pb)) + " parameters of the '" + pb.em.name +
                     "' error model (--noise-model white needs fewer).");
  }
  const bool priors = std::any_of(pb.em.nuisance.begin(), pb.em.nuisance.end(),
                                  [](const NuisanceTerm& t) { return t.prior_sd > 0.0; });
  const bool ou = pb.em.correlation == Correlation::ou;
  const bool refit_profile = c.fit_control.refit_in_noise_profile;
  Noise noise{pb.fixed_w.size() ? pb.fixed_w : pb.unit, 0.0, 0.0, 0.0, 0.0};
  Eigen::VectorXd start = initial_of(m.specs, calibrated);
  if (priors) {  // the priors' weight from the residuals of the start, nuisance free
    const Whitener wh = make_whitener(pb, pb.clusters, noise);
    const Eval ev = evaluate(pb, y, e, start, pb.clusters, wh, noise);
    noise.sigma = std::isfinite(ev.rss) ? std::sqrt(ev.rss / n) : 1.0;
  }
  // alternate: fit the parameters at the current noise state (multi-start the first time),
  // profile the specimen variance ratio with refits, then the offset ratio and the
  // correlation length at the fitted parameters, then re-estimate the weights and the priors'
  // sigma from the residuals; keep the (params, noise) with the lowest AICc, an exact
  // likelihood value at each step
  Noise best_noise = noise;
  FitState best;
  bool found = false;
  m.aicc = std::numeric_limits<double>::infinity();
  // alternations (converged when no weight, variance ratio, correlation length or prior
  // weight moves by more than 1 %; two or three suffice in the tests)
  for (int it = 0; it < std::max(1, c.fit_control.noise_iterations); ++it) {
    FitState fit = fit_clusters(pb, y, e, m.specs, start, pb.clusters, noise,
                                (opt.multi_start || c.multi_start_effects.count(e)) && it == 0);
    auto neg2_at = [&](const Noise& nz, const FitState& fs) {
      const Whitener wh = make_whitener(pb, pb.clusters, nz);
      return neg2_log_likelihood(pb, evaluate_prediction(pb, y, flat, fs.eval.pred, wh, nz), wh, nz);
    };
    const Noise before = noise;
    if (pb.random_effect) {
      double g2_mean = 0.0;
      for (const auto& cl : pb.clusters) {
        g2_mean += cluster_g2(pb, cl, noise.w) / static_cast<double>(pb.clusters.size());
      }
      Eigen::VectorXd warm = fit.fit.params;
      FitState best_rho = fit;
      double best_rho_value = noise.rho;
      double best_rho_f = std::numeric_limits<double>::infinity();
      auto try_rho = [&](double rho) {
        Noise nz = noise;
        nz.rho = rho / g2_mean;
        FitState fs = refit_profile ? fit_clusters(pb, y, e, m.specs, warm, pb.clusters, nz, false)
                                    : fit;
        if (refit_profile) warm = fs.fit.params;
        const double f = neg2_at(nz, fs);
        if (f < best_rho_f) best_rho_f = f, best_rho = fs, best_rho_value = nz.rho;
        return f;
      };
      std::vector<double> grid(std::begin(kRhoGrid), std::end(kRhoGrid));
      profile(try_rho, grid, nullptr);
      noise.rho = best_rho_value;
      fit = best_rho;
    }
    if (pb.em.specimen_offset) {
      double h2_mean = 0.0;
      for (const auto& cl : pb.clusters) {
        h2_mean += cluster_h2(pb, cl, noise.w) / static_cast<double>(pb.clusters.size());
      }
      if (h2_mean > 0.0) {
        auto try_offset = [&](double r) {
          Noise nz = noise;
          nz.rho_offset = r / h2_mean;
          return neg2_at(nz, fit);
        };
        std::vector<double> grid(std::begin(kOffsetGrid), std::end(kOffsetGrid));
        noise.rho_offset = profile(try_offset, grid, nullptr) / h2_mean;
      }
    }
    if (ou) {
      auto try_ell = [&](double ell) {
        Noise nz = noise;
        nz.ell = ell;
        // keep AICc defined for every candidate: n_eff above the largest parameter count
        if (effective_n(pb, nz) < pb.max_params + 2.0) return std::numeric_limits<double>::infinity();
        return neg2_at(nz, fit);
      };
      std::vector<double> grid = {0.0};
      for (int g = 0; g < kEllGrid; ++g) {
        grid.push_back(pb.ell_lo * std::pow(pb.ell_hi / pb.ell_lo, g / (kEllGrid - 1.0)));
      }
      noise.ell = profile(try_ell, grid, nullptr);
      // the white part of the correlated series' variance
      if (noise.ell > 0.0) {
        auto try_nugget = [&](double v) {
          Noise nz = noise;
          nz.nugget = v;
          if (effective_n(pb, nz) < pb.max_params + 2.0) return std::numeric_limits<double>::infinity();
          return neg2_at(nz, fit);
        };
        noise.nugget = profile(try_nugget, std::vector<double>(std::begin(kNuggetGrid), std::end(kNuggetGrid)), nullptr);
      } else {
        noise.nugget = 0.0;
      }
    }
    {
      const Whitener wh = make_whitener(pb, pb.clusters, noise);
      fit.eval = evaluate_prediction(pb, y, flat, fit.eval.pred, wh, noise);
      const double a = aicc_of(neg2_log_likelihood(pb, fit.eval, wh, noise), k,
                               regression_parameters(pb, m.specs.size()), effective_n(pb, noise));
      if (a < m.aicc) {
        m.aicc = a;
        best = fit;
        best_noise = noise;
        found = true;
      }
    }
    double moved = std::max({relative_move(noise.rho, before.rho),
                             relative_move(noise.rho_offset, before.rho_offset),
                             relative_move(noise.ell, before.ell),
                             relative_move(noise.nugget, before.nugget)});
    const bool reweight = !(pb.noise == NoiseModel::pooled || pb.fixed_w.size() > 0 ||
                            (pb.quantities() == 1 && pb.noise == NoiseModel::per_quantity));
    if (reweight) {
      const Eigen::VectorXd w_new = noise_weights(pb, y, in_row_order(flat, fit.eval.pred), noise);
      moved = std::max(moved, (w_new.array().log() - noise.w.array().log()).abs().maxCoeff());
      noise.w = w_new;
    }
    if (priors) {
      const double sigma = std::sqrt(fit.eval.rss / n);
      moved = std::max(moved, relative_move(sigma, noise.sigma));
      noise.sigma = sigma;
    }
    start = fit.fit.params;
    // white residuals without reweighting or priors: the first pass is final, as before
    if (!reweight && !priors && !ou && !pb.em.specimen_offset) break;
    if (it > 0 && moved < 0.01) break;
  }
  // no step had a finite likelihood (predictions or weights not finite): numerical trouble,
  // reported as such rather than evaluated further
  if (!found) {
    throw std::runtime_error("the fit of candidate " + std::string(effect_name(e)) + " to " +
                             c.measured.source + " found no parameters with a finite "
                             "likelihood; the measurements cannot be modelled by it");
  }
  *noise_out = best_noise;
  m.params = best.fit.params;
  finish_fit(pb, y, m, in_row_order(flat, best.eval.pred), best.eval.beta, best.eval.rss,
             best_noise);
  // held-out: refit on each fold's training rows, warm-started at the full-data optimum, with
  // the full-data noise model
  m.heldout_predictions = heldout_predictions(pb, y, e, m.specs, m.params, best_noise);
  m.heldout_rmse = score(pb, y, m.heldout_predictions);
  return m;
}

ModelFit fit_candidate_fixed_noise(const Problem& pb, const Eigen::VectorXd& y, Effect e,
                                   const Eigen::VectorXd& start, const Noise& noise,
                                   bool heldout) {
  ModelFit m;
  m.effect = e;
  m.specs = candidate_specs(pb, e);
  const int k = static_cast<int>(m.specs.size()) + error_parameters(pb);
  const FitState fs = fit_clusters(pb, y, e, m.specs, start, pb.clusters, noise, false);
  const Whitener wh = make_whitener(pb, pb.clusters, noise);
  m.params = fs.fit.params;
  m.aicc = aicc_of(neg2_log_likelihood(pb, fs.eval, wh, noise), k,
                   regression_parameters(pb, m.specs.size()), effective_n(pb, noise));
  if (heldout) {
    m.heldout_predictions = heldout_predictions(pb, y, e, m.specs, m.params, noise);
    m.heldout_rmse = score(pb, y, m.heldout_predictions);
  }
  return m;
}

ModelFit practitioner_baseline(const Problem& pb, const Noise& noise) {
  const DiagnosisCase& c = pb.c;
  ModelFit m;
  m.effect = Effect::none;
  m.model = c.baseline_model;
  m.specs = c.baseline_params;
  const auto rows = all_rows(c.measured.rows.size());
  m.params = c.calibrate_baseline(rows);
  const Eigen::VectorXd none;
  {
    const Whitener wh = make_whitener(pb, pb.clusters, noise);
    const Eval ev = evaluate(pb, pb.y, Effect::none, m.params, pb.clusters, wh, noise);
    finish_fit(pb, pb.y, m, in_row_order(flatten(pb.clusters), ev.pred), ev.beta, ev.rss, noise);
    m.aicc = aicc_of(neg2_log_likelihood(pb, ev, wh, noise),
                     static_cast<int>(m.specs.size()) + error_parameters(pb),
                     regression_parameters(pb, m.specs.size()), effective_n(pb, noise));
  }
  m.heldout_predictions = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(rows.size()), NAN);
  for (const Fold& f : c.folds) {
    const Eigen::VectorXd params = c.calibrate_baseline(f.train);
    const auto train = clusters_of(pb, f.train);
    const Whitener wh = make_whitener(pb, train, noise);
    const Eval ev = evaluate(pb, pb.y, Effect::none, params, train, wh, noise);
    Eigen::VectorXd p = c.predict(Effect::none, params, none, f.test);
    p = heldout_with_nuisance(pb, pb.y, f.test, p, ev.beta, noise);
    for (size_t i = 0; i < f.test.size(); ++i) m.heldout_predictions[f.test[i]] = p[static_cast<Eigen::Index>(i)];
  }
  m.heldout_rmse = score(pb, pb.y, m.heldout_predictions);
  return m;
}

ModelFit trivial_predictor(const Problem& pb, const Eigen::VectorXd& y, const Noise& noise) {
  const DiagnosisCase& c = pb.c;
  const auto n = static_cast<Eigen::Index>(c.measured.rows.size());
  auto predict_rows = [&](const std::vector<int>& train, const std::vector<int>& rows) {
    if (c.trivial_predict) return c.trivial_predict(y, train, rows);
    std::vector<double> sum(static_cast<size_t>(pb.quantities()), 0.0), count(sum.size(), 0.0);
    for (int i : train) {
      sum[static_cast<size_t>(pb.quantity[static_cast<size_t>(i)])] += y[i];
      count[static_cast<size_t>(pb.quantity[static_cast<size_t>(i)])] += 1.0;
    }
    for (size_t q = 0; q < sum.size(); ++q) sum[q] = count[q] > 0.0 ? sum[q] / count[q] : 0.0;
    Eigen::VectorXd p(static_cast<Eigen::Index>(rows.size()));
    for (size_t k = 0; k < rows.size(); ++k) {
      p[static_cast<Eigen::Index>(k)] = sum[static_cast<size_t>(pb.quantity[static_cast<size_t>(rows[k])])];
    }
    return p;
  };
  // the nuisance terms of the trivial predictor, fitted on the training rows like a model's
  auto with_nuisance = [&](const std::vector<int>& train, const std::vector<int>& rows,
                           bool heldout) {
    Eigen::VectorXd p = predict_rows(train, rows);
    if (pb.em.nuisance.empty()) return p;
    const auto cl = clusters_of(pb, train);
    const auto flat = flatten(cl);
    const Whitener wh = make_whitener(pb, cl, noise);
    const Eval ev = evaluate_prediction(pb, y, flat, predict_rows(train, flat), wh, noise);
    if (!heldout) {
      if (ev.beta.size() > 0 && p.allFinite()) p += nuisance_columns(pb, rows, p) * ev.beta;
      return p;
    }
    return heldout_with_nuisance(pb, y, rows, p, ev.beta, noise);
  };
  ModelFit m;
  m.effect = Effect::none;
  m.model = c.trivial_predict ? c.trivial_model : "the measured mean of each quantity (no model)";
  m.aicc = NAN;
  const std::vector<int> all = all_rows(static_cast<size_t>(n));
  m.predictions = with_nuisance(all, all, false);
  m.rss = (m.predictions - y).cwiseProduct(pb.unit).squaredNorm();
  m.rmse = score(pb, y, m.predictions);
  m.heldout_predictions = Eigen::VectorXd::Constant(n, NAN);
  for (const Fold& f : c.folds) {
    const Eigen::VectorXd p = with_nuisance(f.train, f.test, true);
    for (size_t k = 0; k < f.test.size(); ++k) m.heldout_predictions[f.test[k]] = p[static_cast<Eigen::Index>(k)];
  }
  m.heldout_rmse = score(pb, y, m.heldout_predictions);
  return m;
}

void bootstrap(const Problem& pb, ModelFit& m, const Noise& noise, const DiagnosisOptions& opt) {
  if (opt.bootstrap <= 0) return;
  const auto& rows = pb.c.measured.rows;
  std::mt19937_64 rng(opt.seed);
  const Eigen::Index np = m.params.size();
  std::vector<std::vector<double>> samples(static_cast<size_t>(np));
  // specimens resampled within each condition when specimens are given (their scatter
  // dominates); with correlated residuals or nuisance terms the whitened residuals (the
  // innovations of the error model) are resampled and recoloured; otherwise residuals are
  // resampled within each quantity
  const bool recolor = !pb.random_effect && (pb.em.correlation == Correlation::ou ||
                                             !pb.em.nuisance.empty());
  std::map<std::string, std::vector<int>> by_key;  // quantity -> rows, or group -> clusters
  if (pb.random_effect) {
    for (size_t i = 0; i < pb.clusters.size(); ++i) {
      by_key[rows[static_cast<size_t>(pb.clusters[i].front())].group].push_back(static_cast<int>(i));
    }
  } else {
    for (size_t i = 0; i < rows.size(); ++i) by_key[rows[i].quantity].push_back(static_cast<int>(i));
  }
  const Eigen::VectorXd resid = pb.y - m.predictions;
  const auto flat = flatten(pb.clusters);
  Whitener wh;
  Eigen::VectorXd innovations;
  if (recolor) {
    wh = make_whitener(pb, pb.clusters, noise);
    Eigen::VectorXd z(static_cast<Eigen::Index>(flat.size()));
    for (size_t i = 0; i < flat.size(); ++i) z[static_cast<Eigen::Index>(i)] = resid[flat[i]] * noise.w[flat[i]];
    innovations = wh.whiten(z);
  }
  for (int b = 0; b < opt.bootstrap; ++b) {
    FitState fs;
    if (pb.random_effect) {
      std::vector<std::vector<int>> draw;
      for (const auto& [g, members] : by_key) {
        std::uniform_int_distribution<size_t> pick(0, members.size() - 1);
        for (size_t j = 0; j < members.size(); ++j) {
          draw.push_back(pb.clusters[static_cast<size_t>(members[pick(rng)])]);
        }
      }
      fs = fit_clusters(pb, pb.y, m.effect, m.specs, m.params, draw, noise, false);
    } else if (recolor) {
      std::uniform_int_distribution<Eigen::Index> pick(0, innovations.size() - 1);
      Eigen::VectorXd xi(innovations.size());
      for (Eigen::Index i = 0; i < xi.size(); ++i) xi[i] = innovations[pick(rng)];
      const Eigen::VectorXd z = wh.color(xi);
      Eigen::VectorXd y_star = m.predictions;
      for (size_t i = 0; i < flat.size(); ++i) y_star[flat[i]] += z[static_cast<Eigen::Index>(i)] / noise.w[flat[i]];
      fs = fit_clusters(pb, y_star, m.effect, m.specs, m.params, pb.clusters, noise, false);
    } else {
      Eigen::VectorXd y_star = m.predictions;
      for (const auto& [q, members] : by_key) {
        std::uniform_int_distribution<size_t> pick(0, members.size() - 1);
        for (int i : members) y_star[i] += resid[members[pick(rng)]];
      }
      fs = fit_clusters(pb, y_star, m.effect, m.specs, m.params, pb.clusters, noise, false);
    }
    for (Eigen::Index j = 0; j < np; ++j) samples[static_cast<size_t>(j)].push_back(fs.fit.params[j]);
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

}  // namespace kneesim::diagnosis::detail
