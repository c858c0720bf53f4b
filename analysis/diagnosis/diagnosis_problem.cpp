#include "analysis/diagnosis/diagnosis_problem.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <map>
#include <limits>
#include <stdexcept>

#include "engine/errors.h"

namespace kneesim::diagnosis::detail {
namespace {

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

double log_w_sum(const Problem& pb, const Eigen::VectorXd& w) {
  double s = 0.0;
  for (Eigen::Index i = 0; i < w.size(); ++i) s += std::log(w[i] / pb.unit[i]);
  return s;
}

}  // namespace

std::vector<int> flatten(const std::vector<std::vector<int>>& clusters) {
  std::vector<int> rows;
  for (const auto& cl : clusters) rows.insert(rows.end(), cl.begin(), cl.end());
  return rows;
}

std::vector<int> all_rows(size_t n) {
  std::vector<int> rows(n);
  for (size_t i = 0; i < n; ++i) rows[i] = static_cast<int>(i);
  return rows;
}

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

std::vector<ParamSpec> candidate_specs(const Problem& pb, Effect e) {
  std::vector<ParamSpec> specs = pb.c.baseline_params;
  const auto eff = case_effect_params(pb.c, e);
  specs.insert(specs.end(), eff.begin(), eff.end());
  return specs;
}

Problem make_problem(const DiagnosisCase& c, const DiagnosisOptions& options) {
  const auto& rows = c.measured.rows;
  if (rows.empty()) throw InputError(c.measured.source + ": row 2: the file holds no measurements.");
  Problem pb{c, Eigen::VectorXd(static_cast<Eigen::Index>(rows.size())),
             Eigen::VectorXd(static_cast<Eigen::Index>(rows.size())), {}, {}, {}, {}, false,
             NoiseModel::per_quantity, {}, {}, {}, {}, {}, 0.0, 0.0, 0};
  // quantities in order of appearance; unit conversion into the first one by RMS magnitudes
  std::map<std::string, double> sum_sq;
  std::map<std::string, int> count;
  std::map<std::string, int> index;
  for (const auto& r : rows) {
    sum_sq[r.quantity] += r.value * r.value;
    count[r.quantity] += 1;
    if (!index.count(r.quantity)) {
      index[r.quantity] = static_cast<int>(pb.quantity_names.size());
      pb.quantity_names.push_back(r.quantity);
    }
  }
  const std::string first = rows.front().quantity;
  const double ref = std::sqrt(sum_sq[first] / count[first]);
  for (size_t i = 0; i < rows.size(); ++i) {
    const double scale = std::sqrt(sum_sq[rows[i].quantity] / count[rows[i].quantity]);
    pb.y[static_cast<Eigen::Index>(i)] = rows[i].value;
    pb.unit[static_cast<Eigen::Index>(i)] = (scale > 0.0) ? ref / scale : 1.0;
    pb.quantity.push_back(index[rows[i].quantity]);
  }
  // a noise line a + b |f| needs enough residuals per quantity; with fewer, one sd each
  pb.noise = c.noise_model;
  for (const auto& [q, n] : count) {
    if (pb.noise == NoiseModel::proportional && n < kMinRowsProportional) {
      pb.noise = NoiseModel::per_quantity;
    }
  }
  pb.em = select_error_model(c.error_model, options.noise_model, options.noise_params, c.name);

  // specimens: clusters of rows
  std::map<std::string, std::vector<int>> by_specimen;
  bool specimens = true;
  for (size_t i = 0; i < rows.size(); ++i) {
    specimens = specimens && !rows[i].specimen.empty();
    by_specimen[rows[i].group + "/" + rows[i].specimen].push_back(static_cast<int>(i));
  }
  pb.random_effect = specimens && by_specimen.size() >= 4;
  if (!pb.random_effect) pb.em.specimen_offset = false;
  pb.offset_rows.assign(rows.size(), 0);
  if (pb.em.specimen_offset) {
    for (size_t i = 0; i < rows.size(); ++i) pb.offset_rows[i] = pb.quantity[i] == 0;
  }

  // series of the correlation
  std::map<std::string, int> series_index;
  const bool own_keys = c.series_key.size() == rows.size();
  const bool own_x = c.series_x.size() == rows.size();
  for (size_t i = 0; i < rows.size(); ++i) {
    const std::string key = own_keys ? c.series_key[i]
                                     : rows[i].group + "/" + rows[i].specimen + "/" + rows[i].quantity;
    auto it = series_index.find(key);
    if (it == series_index.end()) it = series_index.emplace(key, static_cast<int>(series_index.size())).first;
    pb.series.push_back(it->second);
    pb.sx.push_back(own_x ? c.series_x[i] : rows[i].x);
  }
  if (pb.em.correlation == Correlation::ou) {
    std::map<int, std::vector<double>> xs;
    for (size_t i = 0; i < rows.size(); ++i) xs[pb.series[i]].push_back(pb.sx[i]);
    std::vector<double> spacing;
    double span = 0.0;
    for (auto& [s, v] : xs) {
      std::sort(v.begin(), v.end());
      for (size_t k = 1; k < v.size(); ++k) {
        if (v[k] > v[k - 1]) spacing.push_back(v[k] - v[k - 1]);
      }
      if (v.size() > 1) span = std::max(span, v.back() - v.front());
    }
    if (spacing.empty() || !(span > 0.0)) {
      pb.em.correlation = Correlation::none;  // nothing to correlate along
    } else {
      std::nth_element(spacing.begin(), spacing.begin() + static_cast<long>(spacing.size() / 2),
                       spacing.end());
      pb.ell_lo = 0.25 * spacing[spacing.size() / 2];
      pb.ell_hi = 2.0 * span;
    }
  }

  if (pb.random_effect) {
    for (auto& [key, members] : by_specimen) pb.clusters.push_back(std::move(members));
  } else if (pb.em.correlation == Correlation::ou) {
    std::map<int, std::vector<int>> by_series;
    for (size_t i = 0; i < rows.size(); ++i) by_series[pb.series[i]].push_back(static_cast<int>(i));
    for (auto& [s, members] : by_series) pb.clusters.push_back(std::move(members));
  } else {
    for (size_t i = 0; i < rows.size(); ++i) pb.clusters.push_back({static_cast<int>(i)});
  }
  pb.dg = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(rows.size()));
  for (Effect e : c.candidates) {
    pb.max_params = std::max(pb.max_params, regression_parameters(pb, candidate_specs(pb, e).size()));
  }
  return pb;
}

Whitener make_whitener(const Problem& pb, const std::vector<std::vector<int>>& clusters,
                       const Noise& noise) {
  CovarianceRows rows;
  rows.w = &noise.w;
  rows.dg = pb.random_effect ? &pb.dg : nullptr;
  rows.offset = pb.em.specimen_offset ? &pb.offset_rows : nullptr;
  rows.series = &pb.series;
  rows.x = &pb.sx;
  CovarianceParams p;
  p.rho = pb.random_effect ? noise.rho : 0.0;
  p.rho_offset = pb.em.specimen_offset ? noise.rho_offset : 0.0;
  p.ell = pb.em.correlation == Correlation::ou ? noise.ell : 0.0;
  p.nugget = noise.nugget;
  return Whitener(clusters, rows, p);
}

Eigen::VectorXd predict(const Problem& pb, Effect e, const Eigen::VectorXd& params,
                        const std::vector<int>& rows) {
  const Eigen::Index nb = static_cast<Eigen::Index>(pb.c.baseline_params.size());
  return pb.c.predict(e, params.head(nb), params.tail(params.size() - nb), rows);
}

Eigen::MatrixXd nuisance_columns(const Problem& pb, const std::vector<int>& rows,
                                 const Eigen::VectorXd& pred) {
  const auto m = static_cast<Eigen::Index>(pb.em.nuisance.size());
  Eigen::MatrixXd x(static_cast<Eigen::Index>(rows.size()), m);
  for (Eigen::Index j = 0; j < m; ++j) x.col(j) = pb.em.nuisance[static_cast<size_t>(j)].column(rows, pred);
  return x;
}

Eval evaluate_prediction(const Problem& pb, const Eigen::VectorXd& y,
                         const std::vector<int>& rows, const Eigen::VectorXd& pred,
                         const Whitener& wh, const Noise& noise) {
  Eval ev;
  ev.pred = pred;
  const auto n = static_cast<Eigen::Index>(rows.size());
  if (!pred.allFinite()) {
    ev.resid = Eigen::VectorXd::Constant(n + static_cast<Eigen::Index>(pb.em.nuisance.size()), NAN);
    return ev;
  }
  Eigen::VectorXd z(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const int r = rows[static_cast<size_t>(i)];
    z[i] = (y[r] - pred[i]) * noise.w[r];
  }
  const Eigen::VectorXd zt = wh.whiten(z);
  const auto m = static_cast<Eigen::Index>(pb.em.nuisance.size());
  if (m == 0) {
    ev.resid = zt;
    ev.rss = zt.squaredNorm();
    return ev;
  }
  Eigen::MatrixXd x = nuisance_columns(pb, rows, pred);
  for (Eigen::Index i = 0; i < n; ++i) x.row(i) *= noise.w[rows[static_cast<size_t>(i)]];
  if (!x.allFinite()) {
    ev.resid = Eigen::VectorXd::Constant(n, NAN);
    return ev;
  }
  Eigen::VectorXd lambda(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const double tau = pb.em.nuisance[static_cast<size_t>(j)].prior_sd;
    lambda[j] = tau > 0.0 ? std::pow(noise.sigma / tau, 2) : 0.0;
  }
  ev.beta = solve_nuisance(zt, wh.whiten(x), lambda, &ev.resid);
  ev.rss = ev.resid.squaredNorm();
  for (Eigen::Index j = 0; j < m; ++j) {
    const double tau = pb.em.nuisance[static_cast<size_t>(j)].prior_sd;
    if (tau > 0.0) ev.penalty += std::pow(ev.beta[j] / tau, 2);
  }
  return ev;
}

Eval evaluate(const Problem& pb, const Eigen::VectorXd& y, Effect e,
              const Eigen::VectorXd& params, const std::vector<std::vector<int>>& clusters,
              const Whitener& wh, const Noise& noise) {
  const auto rows = flatten(clusters);
  return evaluate_prediction(pb, y, rows, predict(pb, e, params, rows), wh, noise);
}

FitState fit_clusters(const Problem& pb, const Eigen::VectorXd& y, Effect e,
                      const std::vector<ParamSpec>& specs, const Eigen::VectorXd& start,
                      const std::vector<std::vector<int>>& clusters, const Noise& noise,
                      bool multi) {
  const Whitener wh = make_whitener(pb, clusters, noise);
  const auto m = static_cast<Eigen::Index>(pb.em.nuisance.size());
  auto residuals = [&](const Eigen::VectorXd& p) {
    const Eval ev = evaluate(pb, y, e, p, clusters, wh, noise);
    if (m == 0 || !std::isfinite(ev.rss)) return ev.resid;
    // the priors as extra residuals: |r|^2 + sigma^2 sum (beta / tau)^2
    Eigen::VectorXd out(ev.resid.size() + m);
    out.head(ev.resid.size()) = ev.resid;
    for (Eigen::Index j = 0; j < m; ++j) {
      const double tau = pb.em.nuisance[static_cast<size_t>(j)].prior_sd;
      out[ev.resid.size() + j] = tau > 0.0 ? noise.sigma * ev.beta[j] / tau : 0.0;
    }
    return out;
  };
  PrefetchFn prefetch;
  if (pb.c.prefetch) {
    const Eigen::Index nb = static_cast<Eigen::Index>(pb.c.baseline_params.size());
    prefetch = [&pb, e, nb](const std::vector<Eigen::VectorXd>& points) {
      std::vector<Eigen::VectorXd> effect_params;
      for (const auto& p : points) effect_params.push_back(p.tail(p.size() - nb));
      pb.c.prefetch(e, effect_params);
    };
  }
  FitState s;
  s.fit = fit_least_squares(residuals, specs, start, multi, pb.c.fit_control, prefetch);
  s.eval = evaluate(pb, y, e, s.fit.params, clusters, wh, noise);
  return s;
}

double neg2_log_likelihood(const Problem& pb, const Eval& ev, const Whitener& wh,
                           const Noise& noise) {
  const double n = static_cast<double>(ev.pred.size());
  if (!std::isfinite(ev.rss)) return std::numeric_limits<double>::infinity();
  return n * std::log(std::max(ev.rss, 1e-300) / n) + wh.log_det() - 2.0 * log_w_sum(pb, noise.w) +
         ev.penalty;
}

int error_parameters(const Problem& pb) {
  return noise_params(pb) + (pb.random_effect ? 1 : 0) + (pb.em.specimen_offset ? 1 : 0) +
         (pb.em.correlation == Correlation::ou ? 2 : 0) + static_cast<int>(pb.em.nuisance.size());
}

double effective_n(const Problem& pb, const Noise& noise) {
  return effective_sample_size(pb.series, pb.sx,
                               pb.em.correlation == Correlation::ou ? noise.ell : 0.0,
                               noise.nugget);
}

int regression_parameters(const Problem& pb, size_t model_params) {
  int free = 0;
  for (const auto& t : pb.em.nuisance) free += t.prior_sd > 0.0 ? 0 : 1;
  return static_cast<int>(model_params) + free + 1;
}

double aicc_of(double neg2, int k, int k_r, double n_eff) {
  if (!(n_eff - k_r - 1.0 > 0.0)) return std::numeric_limits<double>::infinity();
  return neg2 + 2.0 * k + 2.0 * k_r * (k_r + 1.0) / (n_eff - k_r - 1.0);
}

double score(const Problem& pb, const Eigen::VectorXd& y, const Eigen::VectorXd& pred) {
  if (pb.noise == NoiseModel::pooled) {  // one sd: the RMSE of the converted residuals
    return std::sqrt((pred - y).cwiseProduct(pb.unit).squaredNorm() /
                     static_cast<double>(pred.size()));
  }
  std::vector<double> ss(static_cast<size_t>(pb.quantities()), 0.0);
  std::vector<double> count(ss.size(), 0.0);
  for (Eigen::Index i = 0; i < pred.size(); ++i) {
    const size_t q = static_cast<size_t>(pb.quantity[static_cast<size_t>(i)]);
    const double d = (pred[i] - y[i]) * pb.unit[i];
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

Eigen::VectorXd heldout_with_nuisance(const Problem& pb, const Eigen::VectorXd& y,
                                      const std::vector<int>& test, const Eigen::VectorXd& pred,
                                      const Eigen::VectorXd& beta_train, const Noise& noise) {
  if (pb.em.nuisance.empty() || !pred.allFinite()) return pred;
  const Eigen::MatrixXd x = nuisance_columns(pb, test, pred);
  Eigen::VectorXd p = pred;
  std::vector<Eigen::Index> free;
  for (size_t j = 0; j < pb.em.nuisance.size(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    if (pb.em.nuisance[j].prior_sd > 0.0) {
      if (jj < beta_train.size() && pb.em.nuisance[j].carried_to_heldout) p += beta_train[jj] * x.col(jj);
    } else {
      free.push_back(jj);
    }
  }
  if (free.empty()) return p;
  // the free terms by generalized least squares over the test rows' clusters
  std::map<int, Eigen::Index> at;
  for (size_t i = 0; i < test.size(); ++i) at[test[i]] = static_cast<Eigen::Index>(i);
  const auto cl = clusters_of(pb, test);
  const auto flat = flatten(cl);
  const Whitener wh = make_whitener(pb, cl, noise);
  Eigen::VectorXd z(static_cast<Eigen::Index>(flat.size()));
  Eigen::MatrixXd xf(z.size(), static_cast<Eigen::Index>(free.size()));
  for (size_t i = 0; i < flat.size(); ++i) {
    const Eigen::Index k = at.at(flat[i]);
    const double w = noise.w[flat[i]];
    z[static_cast<Eigen::Index>(i)] = (y[flat[i]] - p[k]) * w;
    for (size_t j = 0; j < free.size(); ++j) xf(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = x(k, free[j]) * w;
  }
  const Eigen::VectorXd b = solve_nuisance(wh.whiten(z), wh.whiten(xf),
                                           Eigen::VectorXd::Zero(xf.cols()), nullptr);
  for (size_t j = 0; j < free.size(); ++j) p += b[static_cast<Eigen::Index>(j)] * x.col(free[j]);
  return p;
}

Eigen::VectorXd heldout_predictions(const Problem& pb, const Eigen::VectorXd& y, Effect e,
                                    const std::vector<ParamSpec>& specs,
                                    const Eigen::VectorXd& start, const Noise& noise) {
  Eigen::VectorXd out = Eigen::VectorXd::Constant(y.size(), NAN);
  auto fold_prediction = [&](const Fold& f) {
    const FitState fs = fit_clusters(pb, y, e, specs, start, clusters_of(pb, f.train), noise, false);
    Eigen::VectorXd p = predict(pb, e, fs.fit.params, f.test);
    return heldout_with_nuisance(pb, y, f.test, p, fs.eval.beta, noise);
  };
  const auto& folds = pb.c.folds;
  std::vector<Eigen::VectorXd> preds(folds.size());
  if (pb.c.fit_control.threads > 1 && folds.size() > 1) {  // the folds' fits side by side
    std::vector<std::future<Eigen::VectorXd>> runs;
    for (const Fold& f : folds) {
      runs.push_back(std::async(std::launch::async, [&fold_prediction, &f] { return fold_prediction(f); }));
    }
    for (size_t k = 0; k < folds.size(); ++k) preds[k] = runs[k].get();
  } else {
    for (size_t k = 0; k < folds.size(); ++k) preds[k] = fold_prediction(folds[k]);
  }
  for (size_t k = 0; k < folds.size(); ++k) {
    for (size_t i = 0; i < folds[k].test.size(); ++i) out[folds[k].test[i]] = preds[k][static_cast<Eigen::Index>(i)];
  }
  return out;
}
}  // namespace kneesim::diagnosis::detail
