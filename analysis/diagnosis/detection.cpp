#include "analysis/diagnosis/detection.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <thread>

namespace kneesim::diagnosis::detail {
namespace {

// bisection steps on ln(size) per replicate after the bracket (a bracket of 16x resolved to
// 16^(1/16) = 19 %, then interpolated to about 10 %)
constexpr int kBisections = 4;
// the linear-theory start: the bracket spans this factor either side of it
constexpr double kBracket = 4.0;
// sizes scanned (log-spaced) for the largest identifiable signal within the bounds
constexpr int kScan = 16;
// fraction of the way from the null value to the search bound (in the size coordinate) that
// the sizes are searched over
constexpr double kSearchedFraction = 0.8;

// The size coordinate u > 0 of one parameter: value(u) and the largest u within the bounds.
struct SizeAxis {
  ParamSpec spec;
  int index = 0;       // in the effect's parameters
  int direction = 1;   // +1 / -1
  double u_max = 0.0;
  double u_min = 0.0;  // smallest meaningful u (log parameters with null 0: the lower bound)
  double value(double u) const {
    const double null = spec.null_value;
    if (!spec.log_scale) return null + direction * u;
    if (!(null > 0.0)) return u;
    return null * std::exp(direction * u);
  }
};

std::vector<SizeAxis> size_axes(const std::vector<ParamSpec>& specs) {
  std::vector<SizeAxis> out;
  for (size_t i = 0; i < specs.size(); ++i) {
    const ParamSpec& s = specs[i];
    if (!std::isfinite(s.null_value)) continue;
    for (int d : {1, -1}) {
      SizeAxis a{s, static_cast<int>(i), d, 0.0, 0.0};
      if (!s.log_scale) {
        a.u_max = d > 0 ? s.upper - s.null_value : s.null_value - s.lower;
      } else if (!(s.null_value > 0.0)) {
        if (d < 0) continue;
        a.u_max = s.upper;
        a.u_min = s.lower;
      } else {
        a.u_max = d > 0 ? std::log(s.upper / s.null_value) : std::log(s.null_value / s.lower);
      }
      if (a.u_max > a.u_min && a.u_max > 0.0) out.push_back(a);
    }
  }
  return out;
}

// the effect's parameters at the null point: size parameters at their null value, shape
// parameters at their initial value (a log parameter whose null is 0 at its lower bound)
Eigen::VectorXd null_point(const std::vector<ParamSpec>& specs) {
  Eigen::VectorXd p(static_cast<Eigen::Index>(specs.size()));
  for (size_t i = 0; i < specs.size(); ++i) {
    const ParamSpec& s = specs[i];
    double v = std::isfinite(s.null_value) ? s.null_value : s.initial;
    if (s.log_scale && !(v > 0.0)) v = s.lower;
    p[static_cast<Eigen::Index>(i)] = std::clamp(v, s.lower, s.upper);
  }
  return p;
}

double fitted_space(const ParamSpec& s, double v) {
  return s.log_scale ? std::log(std::max(v, s.lower)) : v;
}

// a local linear model of every candidate about its null point and of the baseline about the
// refitted baseline's parameters (forward differences in the fitted space), for forward
// models that are full simulations
struct LinearModel {
  Eigen::VectorXd base_params;
  Eigen::VectorXd f0;                  // baseline at base_params, all rows
  Eigen::MatrixXd jb;                  // d f / d baseline params (fitted space)
  struct Candidate {
    Eigen::VectorXd null_params;       // effect parameters of the linearization point
    Eigen::VectorXd f_null;            // prediction there, all rows
    Eigen::MatrixXd je;                // d f / d effect params (fitted space)
    std::vector<ParamSpec> specs;
  };
  std::map<Effect, Candidate> candidates;
};

std::shared_ptr<LinearModel> linearize(const Problem& pb, const Eigen::VectorXd& base) {
  auto lm = std::make_shared<LinearModel>();
  const auto rows = all_rows(static_cast<size_t>(pb.y.size()));
  const DiagnosisCase& c = pb.c;
  const Eigen::VectorXd none;
  lm->base_params = base;
  lm->f0 = c.predict(Effect::none, base, none, rows);
  auto step_of = [](const ParamSpec& s, double v) { return coarse_difference_step(s, v); };
  auto from_fitted = [](const ParamSpec& s, double z) { return s.log_scale ? std::exp(z) : z; };
  lm->jb.resize(lm->f0.size(), base.size());
  for (Eigen::Index j = 0; j < base.size(); ++j) {
    const ParamSpec& s = c.baseline_params[static_cast<size_t>(j)];
    const double h = step_of(s, base[j]);
    Eigen::VectorXd b = base;
    b[j] = from_fitted(s, fitted_space(s, base[j]) + h);
    lm->jb.col(j) = (c.predict(Effect::none, b, none, rows) - lm->f0) / h;
  }
  if (c.prefetch) {  // every candidate's simulations at once
    for (Effect e : c.candidates) {
      const std::vector<ParamSpec> specs = case_effect_params(c, e);
      const Eigen::VectorXd p0 = null_point(specs);
      std::vector<Eigen::VectorXd> points = {p0};
      for (Eigen::Index j = 0; j < p0.size(); ++j) {
        const ParamSpec& s = specs[static_cast<size_t>(j)];
        Eigen::VectorXd p = p0;
        p[j] = from_fitted(s, fitted_space(s, p[j]) + step_of(s, p0[j]));
        points.push_back(p);
      }
      c.prefetch(e, points);
    }
  }
  for (Effect e : c.candidates) {
    LinearModel::Candidate cand;
    cand.specs = case_effect_params(c, e);
    cand.null_params = null_point(cand.specs);
    cand.f_null = c.predict(e, base, cand.null_params, rows);
    cand.je.resize(cand.f_null.size(), cand.null_params.size());
    for (Eigen::Index j = 0; j < cand.null_params.size(); ++j) {
      const ParamSpec& s = cand.specs[static_cast<size_t>(j)];
      const double h = step_of(s, cand.null_params[j]);
      Eigen::VectorXd p = cand.null_params;
      p[j] = from_fitted(s, fitted_space(s, p[j]) + h);
      cand.je.col(j) = (c.predict(e, base, p, rows) - cand.f_null) / h;
    }
    lm->candidates[e] = std::move(cand);
  }
  return lm;
}

// the case with its forward model replaced by the linear model
DiagnosisCase linear_case(const DiagnosisCase& c, std::shared_ptr<const LinearModel> lm) {
  DiagnosisCase lin = c;
  lin.expensive_forward = false;
  lin.prefetch = nullptr;  // nothing to run ahead: the linear model is evaluated directly
  lin.fit_control.threads = 1;  // cheap fits: the replicates run side by side instead
  lin.predict = [lm, specs = c.baseline_params](Effect e, const Eigen::VectorXd& b,
                                                const Eigen::VectorXd& ep,
                                                const std::vector<int>& rows) {
    Eigen::VectorXd db(b.size());
    for (Eigen::Index j = 0; j < b.size(); ++j) {
      db[j] = fitted_space(specs[static_cast<size_t>(j)], b[j]) -
              fitted_space(specs[static_cast<size_t>(j)], lm->base_params[j]);
    }
    Eigen::VectorXd full;
    if (e == Effect::none || !lm->candidates.count(e)) {
      full = lm->f0 + lm->jb * db;
    } else {
      const auto& cand = lm->candidates.at(e);
      Eigen::VectorXd dp(ep.size());
      for (Eigen::Index j = 0; j < ep.size(); ++j) {
        const ParamSpec& s = cand.specs[static_cast<size_t>(j)];
        dp[j] = fitted_space(s, ep[j]) - fitted_space(s, cand.null_params[j]);
      }
      full = cand.f_null + lm->jb * db + cand.je * dp;
    }
    Eigen::VectorXd out(static_cast<Eigen::Index>(rows.size()));
    for (size_t i = 0; i < rows.size(); ++i) out[static_cast<Eigen::Index>(i)] = full[rows[i]];
    return out;
  };
  return lin;
}

}  // namespace

Signal identifiable_part(const Problem& pb, const Eigen::VectorXd& truth,
                         const Eigen::VectorXd& baseline) {
  // the baseline refitted to the noise-free values: white residuals in the converted units,
  // the free nuisance terms only (a prior-bound term cannot absorb an effect of any size)
  Problem p = pb;
  p.random_effect = false;
  p.em.correlation = Correlation::none;
  p.em.specimen_offset = false;
  std::vector<NuisanceTerm> free_terms;
  for (const auto& t : pb.em.nuisance) {
    if (!(t.prior_sd > 0.0)) free_terms.push_back(t);
  }
  p.em.nuisance = free_terms;
  p.clusters.clear();
  for (Eigen::Index i = 0; i < pb.y.size(); ++i) p.clusters.push_back({static_cast<int>(i)});
  const auto rows = all_rows(static_cast<size_t>(pb.y.size()));
  Noise white{pb.unit, 0.0, 0.0, 0.0, 0.0};
  const FitState fs = fit_clusters(p, truth, Effect::none, pb.c.baseline_params, baseline,
                                   p.clusters, white, false);
  Eigen::VectorXd fitted = fs.eval.pred;
  if (fs.eval.beta.size() > 0) fitted += nuisance_columns(p, rows, fs.eval.pred) * fs.eval.beta;
  Signal s;
  s.delta = truth - fitted;
  s.rms = score(pb, truth, fitted);
  return s;
}

Signal identifiable_signal(const Problem& pb, Effect effect, const Eigen::VectorXd& baseline,
                           const Eigen::VectorXd& effect_params) {
  const auto rows = all_rows(static_cast<size_t>(pb.y.size()));
  Eigen::VectorXd params(baseline.size() + effect_params.size());
  params << baseline, effect_params;
  return identifiable_part(pb, predict(pb, effect, params, rows), baseline);
}

double error_model_rms(const Problem& pb, const Noise& noise, double sigma,
                       const Eigen::VectorXd& prediction) {
  // marginal sd per row: sigma sqrt(C_ii) / w_i, C_ii = 1 + rho g_i^2 + rho_o h_i^2, plus the
  // priored nuisance terms' variance
  const auto rows = all_rows(static_cast<size_t>(pb.y.size()));
  Eigen::VectorXd var(pb.y.size());
  for (Eigen::Index i = 0; i < var.size(); ++i) {
    const double g = pb.random_effect ? pb.dg[i] * noise.w[i] : 0.0;
    const double h = pb.em.specimen_offset && pb.offset_rows[static_cast<size_t>(i)] ? noise.w[i] : 0.0;
    const double cii = 1.0 + noise.rho * g * g + noise.rho_offset * h * h;
    var[i] = sigma * sigma * cii / (noise.w[i] * noise.w[i]);
  }
  if (!pb.em.nuisance.empty()) {
    const Eigen::MatrixXd x = nuisance_columns(pb, rows, prediction);
    for (size_t j = 0; j < pb.em.nuisance.size(); ++j) {
      const double tau = pb.em.nuisance[j].prior_sd;
      if (tau > 0.0) var += (tau * x.col(static_cast<Eigen::Index>(j))).array().square().matrix();
    }
  }
  return score(pb, Eigen::VectorXd::Zero(var.size()), var.cwiseSqrt());
}

DetectionResult detection_limits(const Problem& pb_data, const DiagnosisResult& res,
                                 const Noise& nz, const DiagnosisOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  DetectionResult out;
  out.rate = options.detection_rate;
  out.replicates = options.detection_replicates;
  const ModelFit& none = res.candidates.front();
  const Eigen::VectorXd base = none.params;
  // the forward model of the replicates
  DiagnosisCase lin;
  std::unique_ptr<Problem> owned;
  const Problem* pbp = &pb_data;
  const int threads = std::max(1, pb_data.c.fit_control.threads);
  if (pb_data.c.expensive_forward) {
    out.method = "local linear model of each candidate about its null point";
    lin = linear_case(pb_data.c, linearize(pb_data, base));
    owned = std::make_unique<Problem>(make_problem(lin, options));
    owned->dg = pb_data.dg;
    owned->fixed_w = pb_data.fixed_w;
    pbp = owned.get();
  } else {
    out.method = "refits of the forward model";
  }
  const Problem& pb = *pbp;
  const auto rows = all_rows(static_cast<size_t>(pb.y.size()));
  const Eigen::VectorXd f0 = predict(pb, Effect::none, base, rows);
  // the fitted noise: of the model the data support (the named one; the refitted baseline's
  // when none is named), so that an effect present in the data is not counted as noise
  const double sigma = res.extended().noise.sigma;
  // the replicates' mean is the fitted model of these data with its nuisance terms at their
  // fitted values (a rotation-centre offset far beyond its prior, a cell's offset and drift):
  // each replicate's fit must separate the effect from them again, as the data's did; without
  // them the replicates were cleaner than the data and the limit optimistic (kinematics
  // friction under registration errors: 1.6 times)
  const Eigen::VectorXd fitted_nuisance = res.extended().nuisance_contribution;
  out.noise_rms = error_model_rms(pb, nz, sigma, f0);

  // common random numbers: R noise draws from the fitted error model, shared by every
  // candidate and size
  const int reps = options.detection_replicates;
  std::mt19937_64 rng(options.seed + 7919);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Whitener wh = make_whitener(pb, pb.clusters, nz);
  const auto flat = flatten(pb.clusters);
  const Eigen::MatrixXd xn = pb.em.nuisance.empty() ? Eigen::MatrixXd() : nuisance_columns(pb, rows, f0);
  std::vector<Eigen::VectorXd> draws;
  for (int r = 0; r < reps; ++r) {
    Eigen::VectorXd xi(static_cast<Eigen::Index>(flat.size()));
    for (Eigen::Index i = 0; i < xi.size(); ++i) xi[i] = normal(rng);
    const Eigen::VectorXd z = wh.color(xi);
    Eigen::VectorXd e = Eigen::VectorXd::Zero(pb.y.size());
    for (size_t i = 0; i < flat.size(); ++i) e[flat[i]] += sigma * z[static_cast<Eigen::Index>(i)] / nz.w[flat[i]];
    for (size_t j = 0; j < pb.em.nuisance.size(); ++j) {
      const double tau = pb.em.nuisance[j].prior_sd;
      if (tau > 0.0) e += tau * normal(rng) * xn.col(static_cast<Eigen::Index>(j));
    }
    // the forward model's own error (DiagnosisCase::forward_error_draws): a real effect is
    // not the model's effect exactly, and the replicates must not be cleaner than the data
    if (!pb.c.forward_error_draws.empty()) {
      std::uniform_int_distribution<size_t> pick(0, pb.c.forward_error_draws.size() - 1);
      const Eigen::VectorXd& fe = pb.c.forward_error_draws[pick(rng)];
      if (fe.size() == e.size()) e += fe;
    }
    draws.push_back(e);
  }

  const double ic = options.ic_threshold;
  for (Effect e : pb.c.candidates) {
    const std::vector<ParamSpec> specs = case_effect_params(pb.c, e);
    const Eigen::VectorXd p_null = null_point(specs);
    for (const SizeAxis& axis : size_axes(specs)) {
      auto params_at = [&](double u) {
        Eigen::VectorXd p = p_null;
        p[axis.index] = std::clamp(axis.value(u), axis.spec.lower, axis.spec.upper);
        return p;
      };
      auto full = [&](const Eigen::VectorXd& p) {
        Eigen::VectorXd v(base.size() + p.size());
        v << base, p;
        return v;
      };
      // the searched sizes end where the identifiable signal stops growing (an incubation
      // time far beyond the measurements looks like a lower wear factor, which the baseline
      // absorbs): a size beyond that is not a larger effect
      // and short of the search bound: a fit of an effect at the bound lands on it and is not
      // named by rule, which says nothing about its size
      const double lo_u = axis.u_min > 0.0 ? axis.u_min : 1e-3 * axis.u_max;
      const double u_search = axis.u_min > 0.0
                                  ? lo_u * std::pow(axis.u_max / lo_u, kSearchedFraction)
                                  : kSearchedFraction * axis.u_max;
      double u_top = u_search;
      {
        double best = -1.0;
        for (int g = 0; g <= kScan; ++g) {
          const double u = lo_u * std::pow(u_search / lo_u, static_cast<double>(g) / kScan);
          const double rms = identifiable_signal(pb, e, base, params_at(u)).rms;
          if (!(rms > best)) break;
          best = rms;
          u_top = u;
        }
      }
      // linear theory for the bracket: the whitened identifiable signal at a reference size,
      // scaled to the noncentrality that passes the AICc gate with 80 % chance
      const double u_ref = std::max(axis.u_min, 0.1 * u_top);
      const Signal ref = identifiable_signal(pb, e, base, params_at(u_ref));
      Eigen::VectorXd z(static_cast<Eigen::Index>(flat.size()));
      for (size_t i = 0; i < flat.size(); ++i) z[static_cast<Eigen::Index>(i)] = ref.delta[flat[i]] * nz.w[flat[i]];
      const double q = wh.whiten(z).squaredNorm() / std::max(sigma * sigma, 1e-300);
      const double target = std::pow(0.8416 + std::sqrt(ic + 2.0 * static_cast<double>(specs.size())), 2);
      double u_lin = q > 0.0 ? u_ref * std::sqrt(target / q) : u_top;
      if (axis.spec.log_scale && !(axis.spec.null_value > 0.0)) u_lin = std::max(u_lin, axis.u_min);
      const double u_hi = std::min(u_top, kBracket * u_lin);
      const double u_lo = std::max(axis.u_min, u_hi / (kBracket * kBracket));

      // named as the diagnosis names: the candidate passes every gate and the selection
      // among all supported candidates (lowest AICc, then the tie band's held-out RMSE)
      // picks it; an effect another candidate explains as well is not identified. The other
      // candidates are fitted from their null points; one whose AICc lies beyond e's tie
      // band cannot be named instead of e and skips its held-out refits
      auto named = [&](int r, double u) {
        const Eigen::VectorXd pe = params_at(u);
        Eigen::VectorXd y = f0 + (predict(pb, e, full(pe), rows) - f0) + draws[static_cast<size_t>(r)];
        if (fitted_nuisance.size() == y.size()) y += fitted_nuisance;
        ModelFit n0 = fit_candidate_fixed_noise(pb, y, Effect::none, base, nz, false);
        ModelFit trivial;
        bool heldout_references = false;  // none's and the trivial predictor's, when first needed
        auto gate = [&](ModelFit& m) {
          m.at_bound = find_params_at_bound(m.specs, m.params);
          m.passes_gates = m.aicc < n0.aicc - ic && m.at_bound.empty();
          if (!m.passes_gates) return false;
          if (!heldout_references) {
            n0.heldout_rmse =
                score(pb, y, heldout_predictions(pb, y, Effect::none, n0.specs, n0.params, nz));
            if (options.trivial_gate) trivial.heldout_rmse = trivial_predictor(pb, y, nz).heldout_rmse;
            heldout_references = true;
          }
          m.heldout_rmse = score(pb, y, heldout_predictions(pb, y, m.effect, m.specs, m.params, nz));
          m.passes_gates = passes_gates(m, n0, options);
          m.beats_trivial = beats_trivial(m, trivial, options);
          return is_supported(m);
        };
        ModelFit m = fit_candidate_fixed_noise(pb, y, e, full(pe), nz, false);
        if (!gate(m)) return false;
        DiagnosisResult sel;
        sel.candidates.push_back(n0);
        std::vector<int> supported;
        for (Effect o : pb.c.candidates) {
          const int index = static_cast<int>(sel.candidates.size());
          if (o == e) {
            sel.candidates.push_back(m);
            supported.push_back(index);
            continue;
          }
          ModelFit mo = fit_candidate_fixed_noise(pb, y, o, full(null_point(case_effect_params(pb.c, o))),
                                                  nz, false);
          const bool contends = !options.rank_by_aicc || mo.aicc <= m.aicc + options.tie_aicc;
          if (contends && gate(mo)) supported.push_back(index);
          sel.candidates.push_back(std::move(mo));
        }
        select_among_supported(sel, supported, options);
        return sel.effect() == e;
      };
      auto threshold = [&](int r) {
        double lo = u_lo, hi = u_hi;
        if (!named(r, hi)) {
          if (hi >= u_top || !named(r, u_top)) return std::numeric_limits<double>::infinity();
          lo = hi, hi = u_top;
        } else if (named(r, lo)) {
          return lo;
        }
        for (int b = 0; b < kBisections; ++b) {
          const double mid = std::sqrt(lo * hi);
          (named(r, mid) ? hi : lo) = mid;
        }
        return std::sqrt(lo * hi);
      };
      // the replicates on `threads` threads (each its own noise draw: the same thresholds)
      std::vector<double> thresholds(static_cast<size_t>(reps));
      std::atomic<int> next{0};
      auto worker = [&] {
        for (int r = next++; r < reps; r = next++) thresholds[static_cast<size_t>(r)] = threshold(r);
      };
      std::vector<std::thread> pool;
      for (int t = 1; t < std::min(threads, reps); ++t) pool.emplace_back(worker);
      worker();
      for (auto& th : pool) th.join();
      std::sort(thresholds.begin(), thresholds.end());
      const size_t k = std::min(thresholds.size() - 1,
                                static_cast<size_t>(std::ceil(options.detection_rate * reps)) - 1);
      DetectionLimit lim;
      lim.effect = e;
      lim.param = axis.spec.name;
      lim.null_value = axis.spec.null_value;
      lim.direction = axis.direction;
      lim.replicates = reps;
      lim.reached = std::isfinite(thresholds[k]);
      const double u = lim.reached ? thresholds[k] : u_top;
      lim.value = params_at(u)[axis.index];
      lim.signal_rms = identifiable_signal(pb, e, base, params_at(u)).rms;
      lim.ratio = out.noise_rms > 0.0 ? lim.signal_rms / out.noise_rms : 0.0;
      out.limits.push_back(lim);
    }
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace kneesim::diagnosis::detail
