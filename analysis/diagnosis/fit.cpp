#include "analysis/diagnosis/fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <future>
#include <limits>

namespace kneesim::diagnosis {
namespace {

double to_z(const ParamSpec& s, double v) {
  v = std::clamp(v, s.lower, s.upper);
  return s.log_scale ? std::log(v) : v;
}

double from_z(const ParamSpec& s, double z) {
  const double v = s.log_scale ? std::exp(z) : z;
  return std::clamp(v, s.lower, s.upper);
}

Eigen::VectorXd params_of(const std::vector<ParamSpec>& specs, const Eigen::VectorXd& z) {
  Eigen::VectorXd p(z.size());
  for (Eigen::Index i = 0; i < z.size(); ++i) p[i] = from_z(specs[i], z[i]);
  return p;
}

double sum_sq(const Eigen::VectorXd& r) {
  return r.allFinite() ? r.squaredNorm() : std::numeric_limits<double>::infinity();
}

FitResult levenberg_marquardt(const ResidualsFn& f, const std::vector<ParamSpec>& specs,
                              const Eigen::VectorXd& start, const FitControl& control,
                              const PrefetchFn& prefetch) {
  const Eigen::Index n = start.size();
  Eigen::VectorXd z(n);
  for (Eigen::Index i = 0; i < n; ++i) z[i] = to_z(specs[i], start[i]);
  FitResult out;
  Eigen::VectorXd r = f(params_of(specs, z));
  ++out.evaluations;
  double cost = sum_sq(r);
  double lambda = 1e-3;
  if (n == 0) {  // nothing to fit (a case without baseline parameters, candidate none)
    out.params = start;
    out.rss = cost;
    return out;
  }
  for (int iter = 0; iter < control.max_iterations && std::isfinite(cost); ++iter) {
    // forward-difference Jacobian in z (its points handed to the forward model at once)
    Eigen::MatrixXd jac(r.size(), n);
    std::vector<Eigen::VectorXd> points;
    Eigen::VectorXd steps(n);
    for (Eigen::Index j = 0; j < n; ++j) {
      steps[j] = control.coarse_jacobian
                     ? coarse_difference_step(specs[static_cast<size_t>(j)],
                                              from_z(specs[static_cast<size_t>(j)], z[j]))
                     : 1e-6 * std::max(1.0, std::abs(z[j]));
      Eigen::VectorXd zj = z;
      zj[j] += steps[j];
      points.push_back(params_of(specs, zj));
    }
    if (prefetch) prefetch(points);
    for (Eigen::Index j = 0; j < n; ++j) {
      jac.col(j) = (f(points[static_cast<size_t>(j)]) - r) / steps[j];
      ++out.evaluations;
    }
    const Eigen::MatrixXd jtj = jac.transpose() * jac;
    const Eigen::VectorXd g = jac.transpose() * r;
    bool improved = false;
    for (int tries = 0; tries < 12; ++tries) {
      Eigen::MatrixXd a = jtj;
      a.diagonal() += lambda * (jtj.diagonal().array() + 1e-12).matrix();
      Eigen::VectorXd step = a.ldlt().solve(-g);
      // a parameter the residuals do not depend on here (clamped at a bound, so its column is
      // zero up to rounding: exp(log(b)) differs from b in the last bit) stays put; its
      // near-zero pivot would otherwise turn rounding into a step
      const double diag_max = jtj.diagonal().maxCoeff();
      for (Eigen::Index j = 0; j < n; ++j) {
        if (jtj(j, j) <= 1e-14 * diag_max) step[j] = 0.0;
      }
      Eigen::VectorXd z_new = z + step;
      for (Eigen::Index i = 0; i < n; ++i) z_new[i] = to_z(specs[i], from_z(specs[i], z_new[i]));
      const Eigen::VectorXd r_new = f(params_of(specs, z_new));
      ++out.evaluations;
      const double c_new = sum_sq(r_new);
      if (c_new < cost) {
        const double rel = (cost - c_new) / std::max(cost, 1e-300);
        z = z_new;
        r = r_new;
        cost = c_new;
        lambda = std::max(lambda / 3.0, 1e-9);
        improved = rel > control.tolerance;
        break;
      }
      lambda *= 4.0;
    }
    if (!improved) break;
  }
  out.params = params_of(specs, z);
  out.rss = cost;
  return out;
}

}  // namespace

double coarse_difference_step(const ParamSpec& s, double value) {
  double h = s.log_scale ? 0.05 : 0.02 * (s.upper - s.lower);
  const double up = s.log_scale ? std::log(s.upper) : s.upper;
  if (to_z(s, value) + h > up) h = -h;
  return h;
}

FitResult fit_least_squares(const ResidualsFn& residuals, const std::vector<ParamSpec>& specs,
                            const Eigen::VectorXd& initial, bool multi_start,
                            const FitControl& control, const PrefetchFn& prefetch) {
  std::vector<Eigen::VectorXd> starts = {initial};
  if (multi_start) {
    for (size_t i = 0; i < specs.size(); ++i) {
      const size_t existing = starts.size();
      for (double s : specs[i].starts) {
        for (size_t k = 0; k < existing; ++k) {
          Eigen::VectorXd v = starts[k];
          v[static_cast<Eigen::Index>(i)] = s;
          starts.push_back(v);
        }
      }
    }
  }
  FitResult best;
  best.rss = std::numeric_limits<double>::infinity();
  int evaluations = 0;
  if (prefetch && starts.size() > 1) prefetch(starts);
  std::vector<FitResult> results(starts.size());
  if (control.threads > 1 && starts.size() > 1) {
    std::vector<std::future<FitResult>> runs;
    for (const auto& s : starts) {
      runs.push_back(std::async(std::launch::async, [&, s] {
        return levenberg_marquardt(residuals, specs, s, control, prefetch);
      }));
    }
    for (size_t i = 0; i < runs.size(); ++i) results[i] = runs[i].get();
  } else {
    for (size_t i = 0; i < starts.size(); ++i) {
      results[i] = levenberg_marquardt(residuals, specs, starts[i], control, prefetch);
    }
  }
  for (const FitResult& r : results) {  // in the order of the starts
    evaluations += r.evaluations;
    if (r.rss < best.rss || best.params.size() == 0) best = r;
  }
  best.evaluations = evaluations;
  return best;
}

}  // namespace kneesim::diagnosis
