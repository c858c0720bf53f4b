#include "analysis/study/distribution.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "engine/errors.h"

namespace kneesim::study {
namespace {

// lognormal parameters (mu, sigma of log x) from the variable's mean and sd
void lognormal_params(const Distribution& d, double& mu, double& sigma) {
  const double v = std::log1p((d.sd * d.sd) / (d.mean * d.mean));
  sigma = std::sqrt(v);
  mu = std::log(d.mean) - 0.5 * v;
}

double base_cdf(const Distribution& d, double x) {
  switch (d.kind) {
    case DistributionKind::kNormal:
      return normal_cdf((x - d.mean) / d.sd);
    case DistributionKind::kLognormal: {
      if (x <= 0.0) return 0.0;
      double mu, sigma;
      lognormal_params(d, mu, sigma);
      return normal_cdf((std::log(x) - mu) / sigma);
    }
    case DistributionKind::kUniform:
      return std::clamp((x - d.lo) / (d.hi - d.lo), 0.0, 1.0);
  }
  return 0.0;
}

double base_quantile(const Distribution& d, double u) {
  switch (d.kind) {
    case DistributionKind::kNormal:
      return d.mean + d.sd * normal_quantile(u);
    case DistributionKind::kLognormal: {
      double mu, sigma;
      lognormal_params(d, mu, sigma);
      return std::exp(mu + sigma * normal_quantile(u));
    }
    case DistributionKind::kUniform:
      return d.lo + u * (d.hi - d.lo);
  }
  return 0.0;
}

bool truncated(const Distribution& d) {
  return d.kind != DistributionKind::kUniform && (std::isfinite(d.lo) || std::isfinite(d.hi));
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

double normal_quantile(double p) {
  if (!(p > 0.0 && p < 1.0)) {
    return p <= 0.0 ? -std::numeric_limits<double>::infinity()
                    : std::numeric_limits<double>::infinity();
  }
  // Acklam's rational approximation (relative error 1.15e-9)
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,
                             -2.759285104469687e+02, 1.383577518672690e+02,
                             -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02,
                             -1.556989798598866e+02, 6.680131188771972e+01,
                             -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01,
                             -2.400758277161838e+00, -2.549732539343734e+00,
                             4.374664141464968e+00, 2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01,
                             2.445134137142996e+00, 3.754408661907416e+00};
  const double p_low = 0.02425;
  double x;
  if (p < p_low) {
    const double q = std::sqrt(-2 * std::log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  } else if (p <= 1 - p_low) {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
  } else {
    const double q = std::sqrt(-2 * std::log1p(-p));
    x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  // one Halley step on the exact cdf brings it to full double precision
  const double e = normal_cdf(x) - p;
  const double u = e * std::sqrt(2 * std::numbers::pi) * std::exp(0.5 * x * x);
  return x - u / (1 + 0.5 * x * u);
}

double cdf(const Distribution& d, double x) {
  if (!truncated(d)) return base_cdf(d, x);
  if (x <= d.lo) return 0.0;
  if (x >= d.hi) return 1.0;
  const double f_lo = base_cdf(d, d.lo), f_hi = base_cdf(d, d.hi);
  return (base_cdf(d, x) - f_lo) / (f_hi - f_lo);
}

double quantile(const Distribution& d, double u) {
  if (!truncated(d)) return base_quantile(d, u);
  const double f_lo = base_cdf(d, d.lo), f_hi = base_cdf(d, d.hi);
  return std::clamp(base_quantile(d, f_lo + u * (f_hi - f_lo)), d.lo, d.hi);
}

double from_standard_normal(const Distribution& d, double z) {
  if (d.kind == DistributionKind::kNormal && !truncated(d)) return d.mean + d.sd * z;
  return quantile(d, normal_cdf(z));
}

double mass_outside(const Distribution& d, double lo, double hi) {
  Distribution base = d;
  if (base.kind != DistributionKind::kUniform) {
    base.lo = -std::numeric_limits<double>::infinity();
    base.hi = std::numeric_limits<double>::infinity();
  }
  const double below = std::isfinite(lo) ? base_cdf(base, lo) : 0.0;
  const double above = std::isfinite(hi) ? 1.0 - base_cdf(base, hi) : 0.0;
  return below + above;
}

Distribution parse_distribution(const std::string& text, double nominal,
                                const std::string& where) {
  auto bad = [&](const std::string& why) -> Distribution {
    throw InputError(where + ": distribution '" + text + "' " + why + " (allowed: normal(mean, "
                     "sd), lognormal(mean, sd), uniform(lo, hi), truncnormal(mean, sd, lo, hi); "
                     "'nominal' as a mean is the config's own value)");
  };
  const auto open = text.find('('), close = text.rfind(')');
  if (open == std::string::npos || close == std::string::npos || close < open ||
      text.find_first_not_of(" ", close + 1) != std::string::npos) {
    return bad("is not of the form name(numbers)");
  }
  std::string name = text.substr(0, open);
  name.erase(std::remove(name.begin(), name.end(), ' '), name.end());
  std::vector<double> args;
  std::string inner = text.substr(open + 1, close - open - 1) + ",";
  for (size_t start = 0, comma; (comma = inner.find(',', start)) != std::string::npos;
       start = comma + 1) {
    std::string a = inner.substr(start, comma - start);
    a.erase(std::remove(a.begin(), a.end(), ' '), a.end());
    if (a == "nominal") {
      args.push_back(nominal);
      continue;
    }
    char* end = nullptr;
    const double v = std::strtod(a.c_str(), &end);
    if (a.empty() || *end != '\0' || !std::isfinite(v)) return bad("has a bad number '" + a + "'");
    args.push_back(v);
  }
  Distribution d;
  auto need = [&](size_t n) {
    if (args.size() != n) bad("needs " + std::to_string(n) + " numbers");
  };
  if (name == "normal" || name == "lognormal" || name == "truncnormal") {
    need(name == "truncnormal" ? 4 : 2);
    d.kind = name == "lognormal" ? DistributionKind::kLognormal : DistributionKind::kNormal;
    d.mean = args[0];
    d.sd = args[1];
    if (!(d.sd > 0.0)) bad("has sd = " + fmt(d.sd) + "; the standard deviation must be positive");
    if (d.kind == DistributionKind::kLognormal && !(d.mean > 0.0))
      bad("has mean = " + fmt(d.mean) + "; a lognormal's mean must be positive");
    if (name == "truncnormal") {
      d.lo = args[2];
      d.hi = args[3];
      if (!(d.lo < d.hi)) bad("has lo >= hi");
      if (!(d.mean > d.lo - 10 * d.sd && d.mean < d.hi + 10 * d.sd))
        bad("keeps almost no mass inside [lo, hi]");
    }
  } else if (name == "uniform") {
    need(2);
    d.kind = DistributionKind::kUniform;
    d.lo = args[0];
    d.hi = args[1];
    if (!(d.lo < d.hi)) bad("has lo >= hi");
    d.mean = 0.5 * (d.lo + d.hi);
    d.sd = (d.hi - d.lo) / std::sqrt(12.0);
  } else {
    return bad("has an unknown name '" + name + "'");
  }
  return d;
}

std::string describe(const Distribution& d) {
  switch (d.kind) {
    case DistributionKind::kUniform:
      return "uniform(" + fmt(d.lo) + ", " + fmt(d.hi) + ")";
    case DistributionKind::kLognormal:
    case DistributionKind::kNormal: {
      const std::string base =
          std::string(d.kind == DistributionKind::kLognormal ? "lognormal(" : "normal(") +
          fmt(d.mean) + ", " + fmt(d.sd) + ")";
      if (!truncated(d)) return base;
      return base + " truncated to [" + fmt(d.lo) + ", " + fmt(d.hi) + "]";
    }
  }
  return "";
}

}  // namespace kneesim::study
