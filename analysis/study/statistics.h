// Statistics of study results: percentiles, mean and sample SD, Pearson correlation (the
// sensitivity factor of Pal 2008 is |r| between an input and a measure over the trials), and
// the advanced mean value method (AMV, Wu, Millwater & Cruse 1990) for scalar measures.
//
// AMV: with independent inputs mapped to standard normal coordinates z (x = F^-1(Phi(z))),
// the mean-value first-order model g(z) ~ g0 + a . z comes from one run at z = 0 and one run
// per input at z = h e_j (a_j = (g(h e_j) - g0) / h). For probability level p the most probable
// point of that linear model is z* = Phi^-1(p) a / |a|, where its p-percentile
// g0 + Phi^-1(p) |a| is reached; AMV corrects it with one full run at z*: the p-percentile
// estimate is g(z*). For g linear in normal inputs it is exact; for mildly nonlinear g it keeps
// the first-order MPP but the true value of g there.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace kneesim::study {

// percentile p in [0, 1] of the values (linear interpolation between order statistics, the
// "type 7" rule of Hyndman & Fan 1996: position p (n - 1)); NaN when empty
double percentile(std::vector<double> values, double p);
double mean(const std::vector<double>& values);
double sample_sd(const std::vector<double>& values);  // n - 1 in the denominator
// Pearson correlation of paired values; 0 when either has no spread
double pearson(const std::vector<double>& x, const std::vector<double>& y);

// the first-order model of one scalar measure from the AMV design runs
struct MeanValueModel {
  double g0 = 0.0;      // at z = 0
  Eigen::VectorXd a;    // dg/dz_j, one-at-a-time forward differences
};
MeanValueModel make_mean_value_model(double g0, const std::vector<double>& g_at_steps,
                                     double step);
// the mean-value (first-order) p-percentile g0 + Phi^-1(p) |a|
double mean_value_percentile(const MeanValueModel& m, double p);
// the most probable point of the linear model at level p (z = 0 when a = 0)
Eigen::VectorXd most_probable_point(const MeanValueModel& m, double p);

}  // namespace kneesim::study
