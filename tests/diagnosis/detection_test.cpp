// Detection limits (analysis/diagnosis/detection.h) against the closed form of a linear model
// with white noise: for y = b + s x + e, e ~ N(0, sigma^2), the likelihood-ratio statistic of
// the slope is noncentral chi^2 with one degree of freedom and noncentrality
// lambda = s^2 Sxx / sigma^2; the AICc gate (drop > T, T = threshold + 2 + the small-sample
// terms' difference) is passed with probability 0.8 at lambda_80 = (z_0.8 + sqrt(T))^2, so
// s_80 = sigma sqrt(lambda_80 / Sxx). The simulation also applies the held-out gates, which
// bind little at that size here; required: within 15 % of the closed form (200 replicates:
// the 80th percentile's sampling error is about 5 %).
// Also: the identifiable signal of an effect the baseline absorbs completely is zero.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "analysis/diagnosis/diagnose.h"

using namespace kneesim::diagnosis;

namespace {

DiagnosisCase slope_case(double sigma, std::uint64_t seed) {
  DiagnosisCase c;
  c.name = "slope";
  c.measured.source = "slope.csv";
  c.measured.x_name = "x";
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (int i = 0; i < 40; ++i) {
    const double x = i % 20;
    c.measured.rows.push_back({i < 20 ? "a" : "b", "", "y_mm", x, 3.0 + noise(rng), i + 2});
  }
  c.baseline_model = "constant";
  c.baseline_params = {{"b_mm", "level", -100.0, 100.0, 0.0, false, {}}};
  c.candidates = {Effect::running_in};
  c.effect_params = [](Effect) {
    return std::vector<ParamSpec>{{"s_mm", "slope", -1.0, 1.0, 0.0, false, {}, false, 0.0}};
  };
  auto rows = c.measured.rows;
  c.predict = [rows](Effect e, const Eigen::VectorXd& b, const Eigen::VectorXd& ep,
                     const std::vector<int>& idx) {
    Eigen::VectorXd v(static_cast<Eigen::Index>(idx.size()));
    for (size_t i = 0; i < idx.size(); ++i) {
      const double x = rows[static_cast<size_t>(idx[i])].x;
      v[static_cast<Eigen::Index>(i)] = b[0] + (e == Effect::none ? 0.0 : ep[0] * x);
    }
    return v;
  };
  c.calibrate_baseline = [rows](const std::vector<int>& train) {
    double s = 0.0;
    for (int i : train) s += rows[static_cast<size_t>(i)].value;
    return Eigen::VectorXd::Constant(1, s / static_cast<double>(train.size()));
  };
  c.split_rule = "leave-one-group-out";
  c.folds = make_leave_one_out_folds(c.measured.rows, false, "group");
  return c;
}

}  // namespace

TEST_CASE("detection limit of a slope in white noise agrees with the closed form") {
  const double sigma = 0.3;
  const DiagnosisCase c = slope_case(sigma, 11);
  DiagnosisOptions opt;
  opt.bootstrap = 0;
  opt.detection_replicates = 200;
  const DiagnosisResult r = diagnose(c, opt);
  REQUIRE(r.effect() == Effect::none);
  // two limits: positive and negative slope
  REQUIRE(r.detection.limits.size() == 2);
  const double n = 40.0, k0 = 2.0, k1 = 3.0;
  const double t = opt.ic_threshold + 2.0 + 2.0 * k1 * (k1 + 1.0) / (n - k1 - 1.0) -
                   2.0 * k0 * (k0 + 1.0) / (n - k0 - 1.0);
  const double lambda80 = std::pow(0.8416 + std::sqrt(t), 2);
  const double sxx = 2.0 * 665.0;
  // the profiled sigma of the data, as the simulation uses it
  const double s_sigma = r.candidates.front().noise.sigma;
  const double s80 = s_sigma * std::sqrt(lambda80 / sxx);
  for (const DetectionLimit& d : r.detection.limits) {
    INFO("direction " << d.direction << ": limit " << d.value << " against " << d.direction * s80);
    CHECK(d.reached);
    CHECK(std::abs(d.value) == doctest::Approx(s80).epsilon(0.15));
    // the signal at the limit: the slope's part orthogonal to the level, RMS over the rows
    CHECK(d.signal_rms == doctest::Approx(std::abs(d.value) * std::sqrt(sxx / n)).epsilon(0.01));
    CHECK(d.ratio == doctest::Approx(d.signal_rms / r.detection.noise_rms));
  }
  CHECK(r.detection.noise_rms == doctest::Approx(s_sigma).epsilon(1e-6));
}

TEST_CASE("the identifiable signal of an effect the baseline absorbs is zero") {
  DiagnosisCase c = slope_case(0.3, 12);
  // an "effect" that only shifts the level: absorbed by b
  auto rows = c.measured.rows;
  c.predict = [rows](Effect e, const Eigen::VectorXd& b, const Eigen::VectorXd& ep,
                     const std::vector<int>& idx) {
    return Eigen::VectorXd::Constant(static_cast<Eigen::Index>(idx.size()),
                                     b[0] + (e == Effect::none ? 0.0 : ep[0])).eval();
  };
  CHECK(identifiable_signal_rms(c, Effect::running_in, Eigen::VectorXd::Constant(1, 3.0),
                                Eigen::VectorXd::Constant(1, 0.5)) < 1e-6);
  const DiagnosisCase line = slope_case(0.3, 12);
  CHECK(identifiable_signal_rms(line, Effect::running_in, Eigen::VectorXd::Constant(1, 3.0),
                                Eigen::VectorXd::Constant(1, 0.1)) ==
        doctest::Approx(0.1 * std::sqrt(665.0 / 20.0)).epsilon(1e-3));
}
