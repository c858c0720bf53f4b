// Input distributions of a probabilistic study (Pal 2008: independent normal variables; also
// lognormal, uniform and truncated normal). Every distribution is sampled through its quantile
// function x = F^-1(u): Monte Carlo and Latin hypercube draw u in (0, 1), the advanced mean
// value method maps standard-normal coordinates z through u = Phi(z), so one code path serves
// all methods and the inputs stay independent.
//
// Truncation: a distribution may carry bounds [lo, hi]; its quantile is then the base quantile
// over [F(lo), F(hi)], i.e. the base distribution conditioned on the interval. The study
// truncates every variable to its config key's physical range and reports the probability mass
// that removes; more than kNegligibleMass is an input error unless truncation is allowed.
#pragma once

#include <limits>
#include <string>

namespace kneesim::study {

enum class DistributionKind { kNormal, kLognormal, kUniform };

struct Distribution {
  DistributionKind kind = DistributionKind::kNormal;
  // normal and lognormal: mean and standard deviation of the variable itself (a lognormal's
  // parameters are derived from them); uniform: mean and sd of the uniform on [lo, hi]
  double mean = 0.0, sd = 1.0;
  double lo = -std::numeric_limits<double>::infinity();  // truncation (or uniform) bounds
  double hi = std::numeric_limits<double>::infinity();
};

// below this removed mass a truncation at physical bounds is reported but needs no permission
inline constexpr double kNegligibleMass = 1e-6;

// standard normal cumulative distribution and its inverse (|error| < 1e-15 relative: Acklam's
// rational approximation refined by one Halley step on erfc)
double normal_cdf(double z);
double normal_quantile(double p);  // p in (0, 1)

// cumulative distribution and quantile, truncation included
double cdf(const Distribution& d, double x);
double quantile(const Distribution& d, double u);  // u in (0, 1)
// x of standard-normal coordinate z; for an untruncated normal exactly mean + sd z
double from_standard_normal(const Distribution& d, double z);

// probability mass of the untruncated distribution outside [lo, hi]
double mass_outside(const Distribution& d, double lo, double hi);

// parses "normal(mean, sd)", "lognormal(mean, sd)", "uniform(lo, hi)",
// "truncnormal(mean, sd, lo, hi)"; the word "nominal" for a mean stands for `nominal`.
// Throws InputError naming `where` and the text for bad syntax, sd <= 0, lo >= hi, or a
// lognormal with mean <= 0.
Distribution parse_distribution(const std::string& text, double nominal, const std::string& where);

// "normal(0.07, 0.01)" and the like, for outputs
std::string describe(const Distribution& d);

}  // namespace kneesim::study
