#include "analysis/study/statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/study/distribution.h"

namespace kneesim::study {

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const double pos = std::clamp(p, 0.0, 1.0) * static_cast<double>(v.size() - 1);
  const size_t k = static_cast<size_t>(std::floor(pos));
  if (k + 1 >= v.size()) return v.back();
  const double f = pos - static_cast<double>(k);
  return v[k] + f * (v[k + 1] - v[k]);
}

double mean(const std::vector<double>& v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double sample_sd(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  const double m = mean(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

double pearson(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = std::min(x.size(), y.size());
  if (n < 2) return 0.0;
  const std::vector<double> xs(x.begin(), x.begin() + n), ys(y.begin(), y.begin() + n);
  const double mx = mean(xs), my = mean(ys);
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (size_t i = 0; i < n; ++i) {
    sxy += (xs[i] - mx) * (ys[i] - my);
    sxx += (xs[i] - mx) * (xs[i] - mx);
    syy += (ys[i] - my) * (ys[i] - my);
  }
  if (sxx <= 0.0 || syy <= 0.0) return 0.0;
  return sxy / std::sqrt(sxx * syy);
}

MeanValueModel make_mean_value_model(double g0, const std::vector<double>& g_at_steps,
                                     double step) {
  MeanValueModel m;
  m.g0 = g0;
  m.a.resize(static_cast<Eigen::Index>(g_at_steps.size()));
  for (size_t j = 0; j < g_at_steps.size(); ++j) m.a[j] = (g_at_steps[j] - g0) / step;
  return m;
}

double mean_value_percentile(const MeanValueModel& m, double p) {
  return m.g0 + normal_quantile(p) * m.a.norm();
}

Eigen::VectorXd most_probable_point(const MeanValueModel& m, double p) {
  const double norm = m.a.norm();
  if (norm == 0.0) return Eigen::VectorXd::Zero(m.a.size());
  return normal_quantile(p) * m.a / norm;
}

}  // namespace kneesim::study
