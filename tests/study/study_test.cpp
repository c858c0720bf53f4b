// The study driver on analytic functions, whose percentiles and correlations are known in
// closed form. References: the normal quantile's published values; percentiles of a linear
// function of normals (normal, sd = sqrt(sum (c_j sd_j)^2)) within 4 standard errors of the
// sample percentile (SE = sqrt(p (1 - p) / n) / f(q), f the density at the quantile); AMV exact
// (to rounding) for a linear function and within a stated 3 % for a mildly nonlinear one,
// against a 10^6-sample Monte Carlo reference computed here; Pearson |r| of a linear model
// equal to c_j sd_j / sd(g) within sampling error, ranking the inputs by c_j sd_j;
// byte-identical trials.csv for 1 and 2 threads and for an interrupted and resumed study.
#include <doctest/doctest.h>

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "analysis/study/distribution.h"
#include "analysis/study/ranks.h"
#include "analysis/study/sampling.h"
#include "analysis/study/statistics.h"
#include "analysis/study/study.h"
#include "analysis/study/variables.h"
#include "engine/errors.h"
#include "engine/io/atomic_file.h"
#include "models/config.h"

namespace s = kneesim::study;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("kneesim_study_test_" + name + "_" +
                                                  std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

s::StudyVariable normal_var(const std::string& key, double mean, double sd) {
  s::StudyVariable v;
  v.key = key;
  v.label = key;
  v.nominal = mean;
  v.distribution.mean = mean;
  v.distribution.sd = sd;
  return v;
}

// g = c0 + sum c_j x_j, x_j ~ N(mean_j, sd_j)
s::StudyProblem linear_problem(double c0, std::vector<double> c, std::vector<double> sd) {
  s::StudyProblem p;
  for (size_t j = 0; j < c.size(); ++j) p.variables.push_back(normal_var("x" + std::to_string(j), 0.0, sd[j]));
  p.measures = {"g"};
  p.evaluate = [c0, c](const std::vector<double>& x) {
    s::TrialOutcome o;
    double g = c0;
    for (size_t j = 0; j < c.size(); ++j) g += c[j] * x[j];
    o.scalars = {g};
    return o;
  };
  return p;
}

s::StudyOptions options(const fs::path& out, s::Method m, long trials, int threads = 2) {
  s::StudyOptions o;
  o.method = m;
  o.trials = trials;
  o.seed = 7;
  o.out = out;
  o.quiet = true;
  o.threads = threads;
  o.identity = 42;
  return o;
}

std::vector<double> measure(const s::StudyResult& r, size_t m) {
  std::vector<double> v;
  for (const auto& t : r.records)
    if (t.ok) v.push_back(t.scalars[m]);
  return v;
}

const s::Ranks& ranks() {
  static const s::Ranks r;
  return r;
}

}  // namespace

TEST_CASE("normal quantile: published values and the cdf round trip") {
  CHECK(s::normal_quantile(0.975) == doctest::Approx(1.959963984540054).epsilon(1e-14));
  CHECK(s::normal_quantile(0.99) == doctest::Approx(2.326347874040841).epsilon(1e-14));
  CHECK(s::normal_quantile(0.5) == doctest::Approx(0.0).epsilon(1e-15));
  for (double p : {1e-10, 1e-4, 0.01, 0.3, 0.7, 0.99, 1 - 1e-8})
    CHECK(s::normal_cdf(s::normal_quantile(p)) == doctest::Approx(p).epsilon(1e-12).scale(0));
}

TEST_CASE("distributions: quantiles, truncation, and parse errors") {
  const s::Distribution n = s::parse_distribution("normal(3, 0.5)", 0, "t");
  CHECK(s::quantile(n, 0.5) == doctest::Approx(3.0));
  const s::Distribution u = s::parse_distribution("uniform(1, 3)", 0, "t");
  CHECK(s::quantile(u, 0.25) == doctest::Approx(1.5));
  const s::Distribution ln = s::parse_distribution("lognormal(2, 0.5)", 0, "t");
  CHECK(s::quantile(ln, 1e-9) > 0.0);  // never negative
  // the median of a lognormal with mean m and sd s is m / sqrt(1 + s^2/m^2)
  CHECK(s::quantile(ln, 0.5) == doctest::Approx(2.0 / std::sqrt(1 + 0.0625)).epsilon(1e-12));
  const s::Distribution t = s::parse_distribution("truncnormal(0, 1, -1, 2)", 0, "t");
  for (double p : {1e-6, 0.3, 0.999999}) {
    CHECK(s::quantile(t, p) >= -1.0);
    CHECK(s::quantile(t, p) <= 2.0);
    CHECK(s::cdf(t, s::quantile(t, p)) == doctest::Approx(p).epsilon(1e-9).scale(0));
  }
  CHECK(s::parse_distribution("normal(nominal, 0.01)", 0.07, "t").mean == 0.07);
  CHECK_THROWS_AS(s::parse_distribution("normal(3, 0)", 0, "t"), kneesim::InputError);
  CHECK_THROWS_AS(s::parse_distribution("normal(3, -1)", 0, "t"), kneesim::InputError);
  CHECK_THROWS_AS(s::parse_distribution("gauss(3, 1)", 0, "t"), kneesim::InputError);
  CHECK_THROWS_AS(s::parse_distribution("uniform(3, 1)", 0, "t"), kneesim::InputError);
  CHECK_THROWS_AS(s::parse_distribution("lognormal(-1, 1)", 0, "t"), kneesim::InputError);
}

TEST_CASE("variables: unknown key, non-physical distribution, truncation reported") {
  const kneesim::models::Config c = kneesim::models::load_config("", {});
  CHECK_THROWS_WITH_AS(s::make_variable(c, "rig.no_such_key=normal(1, 0.1)", false),
                       doctest::Contains("not a number key"), kneesim::InputError);
  CHECK_THROWS_WITH_AS(s::make_variable(c, "contact.friction=normal(nominal, 0)", false),
                       doctest::Contains("must be positive"), kneesim::InputError);
  // friction 0.07 +- 0.1 reaches below 0 with probability 0.24: refused, or truncated
  CHECK_THROWS_WITH_AS(s::make_variable(c, "contact.friction=normal(nominal, 0.1)", false),
                       doctest::Contains("--allow-truncation"), kneesim::InputError);
  CHECK_THROWS_AS(s::make_variable(c, "rig.restraint.k_anterior_N_per_mm=normal(4.75, 4)", false),
                  kneesim::InputError);
  const s::StudyVariable t = s::make_variable(c, "contact.friction=normal(nominal, 0.1)", true);
  CHECK(t.removed_mass == doctest::Approx(s::normal_cdf(-0.7)).epsilon(1e-9).scale(0));
  CHECK(s::quantile(t.distribution, 1e-9) >= 0.0);
  // Pal 2008's 13 on the default config: centred on the config's values, nothing truncated
  const auto pal = s::pal2008_variables(c, false);
  REQUIRE(pal.size() == 13);
  for (const auto& v : pal) CHECK(v.removed_mass < s::kNegligibleMass);
  CHECK(pal[11].key == "contact.friction");
  CHECK(pal[11].nominal == 0.07);
}

TEST_CASE("Monte Carlo and Latin hypercube percentiles of a linear function within sampling error") {
  // g = 1 + x0 + 2 x1, x ~ N(0, 1): g ~ N(1, sqrt(5))
  const double sd = std::sqrt(5.0);
  const long n = 2000;
  for (s::Method m : {s::Method::kMonteCarlo, s::Method::kLatinHypercube}) {
    CAPTURE(s::method_name(m));
    const fs::path out = temp_dir(std::string("pct_") + s::method_name(m));
    const auto r = s::run_study(linear_problem(1.0, {1, 2}, {1, 1}), options(out, m, n), ranks());
    const std::vector<double> g = measure(r, 0);
    REQUIRE(g.size() == static_cast<size_t>(n));
    for (double p : {0.01, 0.5, 0.99}) {
      const double q = s::normal_quantile(p);
      const double density = std::exp(-0.5 * q * q) / std::sqrt(2 * M_PI) / sd;
      const double se = std::sqrt(p * (1 - p) / n) / density;
      CAPTURE(p);
      CHECK(std::abs(s::percentile(g, p) - (1.0 + sd * q)) < 4 * se);
    }
    CHECK(fs::exists(out / "summary.json"));
    CHECK(fs::exists(out / "trials.csv"));
    fs::remove_all(out);
  }
}

TEST_CASE("AMV: exact for a linear function of normals, within 3 % for a mildly nonlinear one") {
  // linear: g = 3 + 2 x0 - x1 + 0.5 x2, sds 0.5, 2, 1
  {
    const fs::path out = temp_dir("amv_linear");
    const auto r = s::run_study(linear_problem(3.0, {2, -1, 0.5}, {0.5, 2, 1}),
                                options(out, s::Method::kAdvancedMeanValue, 0), ranks());
    const double sd = std::sqrt(1.0 + 4.0 + 0.25);
    std::map<std::string, double> by_point;
    for (const auto& t : r.records) by_point[t.point] = t.scalars[0];
    CHECK(r.records.size() == 1 + 3 + 2);  // mean, 3 gradients, 2 levels
    CHECK(by_point.at("mpp:g:p01") == doctest::Approx(3.0 + sd * s::normal_quantile(0.01)).epsilon(1e-12));
    CHECK(by_point.at("mpp:g:p99") == doctest::Approx(3.0 + sd * s::normal_quantile(0.99)).epsilon(1e-12));
    fs::remove_all(out);
  }
  // mildly nonlinear: g = x0 + 0.1 x0^2 + x1, x ~ N(0, 1)
  {
    s::StudyProblem p;
    p.variables = {normal_var("x0", 0, 1), normal_var("x1", 0, 1)};
    p.measures = {"g"};
    auto g = [](double x0, double x1) { return x0 + 0.1 * x0 * x0 + x1; };
    p.evaluate = [g](const std::vector<double>& x) {
      s::TrialOutcome o;
      o.scalars = {g(x[0], x[1])};
      return o;
    };
    const fs::path out = temp_dir("amv_nonlinear");
    const auto r = s::run_study(p, options(out, s::Method::kAdvancedMeanValue, 0), ranks());
    std::map<std::string, double> by_point;
    for (const auto& t : r.records) by_point[t.point] = t.scalars[0];
    // reference: 10^6 Monte Carlo samples of g itself (percentile SE < 0.01)
    s::SplitMix64 rng(123);
    std::vector<double> ref;
    for (int i = 0; i < 1000000; ++i)
      ref.push_back(g(s::normal_quantile(rng.uniform()), s::normal_quantile(rng.uniform())));
    for (const char* level : {"p01", "p99"}) {
      const double exact = s::percentile(ref, level[1] == '0' ? 0.01 : 0.99);
      const double amv = by_point.at(std::string("mpp:g:") + level);
      CAPTURE(level);
      CAPTURE(exact);
      CAPTURE(amv);
      CHECK(std::abs(amv - exact) < 0.03 * std::abs(exact));
    }
    fs::remove_all(out);
  }
}

TEST_CASE("correlation sensitivities of a linear model rank the inputs by coefficient x SD") {
  // c = (1, 3, 2), sd = (3, 0.5, 1): c sd = (3, 1.5, 2), sd(g) = sqrt(15.25)
  const fs::path out = temp_dir("sens");
  const auto r = s::run_study(linear_problem(0.0, {1, 3, 2}, {3, 0.5, 1}),
                              options(out, s::Method::kLatinHypercube, 1000), ranks());
  std::ifstream in(out / "sensitivity.csv");
  std::string line;
  std::getline(in, line);
  CHECK(line == "parameter,measure,abs_corr");
  std::map<std::string, double> corr;
  while (std::getline(in, line)) {
    const auto a = line.find(','), b = line.rfind(',');
    corr[line.substr(0, a)] = std::stod(line.substr(b + 1));
  }
  const double sdg = std::sqrt(15.25);
  CHECK(corr.at("x0") > corr.at("x2"));
  CHECK(corr.at("x2") > corr.at("x1"));
  // |r| within 3 standard errors (1 - r^2) / sqrt(n) of c sd / sd(g)
  for (auto [k, cs] : {std::pair{"x0", 3.0}, {"x1", 1.5}, {"x2", 2.0}}) {
    const double rho = cs / sdg;
    CHECK(std::abs(corr.at(k) - rho) < 3 * (1 - rho * rho) / std::sqrt(1000.0));
  }
  fs::remove_all(out);
}

TEST_CASE("trials.csv is byte-identical for 1 and 2 threads; failed trials recorded and counted") {
  s::StudyProblem p = linear_problem(0.5, {1, -2}, {1, 0.3});
  p.curves = {{"c", "t", {0, 1, 2}, "envelopes.csv"}};
  p.evaluate = [](const std::vector<double>& x) {
    s::TrialOutcome o;
    if (x[0] > 2.0) {  // numerical trouble in the tail
      o.ok = false;
      o.failure = "runaway penetration";
      return o;
    }
    o.scalars = {0.5 + x[0] - 2 * x[1]};
    o.curves = {{x[0], x[0] + x[1], x[0] * x[1]}};
    return o;
  };
  const fs::path a = temp_dir("threads1"), b = temp_dir("threads2");
  const auto r1 = s::run_study(p, options(a, s::Method::kMonteCarlo, 300, 1), ranks());
  const auto r2 = s::run_study(p, options(b, s::Method::kMonteCarlo, 300, 2), ranks());
  const std::string t1 = kneesim::io::read_file(a / "trials.csv");
  CHECK(t1 == kneesim::io::read_file(b / "trials.csv"));
  CHECK(kneesim::io::read_file(a / "envelopes.csv") == kneesim::io::read_file(b / "envelopes.csv"));
  CHECK(r1.failed > 0);  // P(x0 > 2) = 2.3 %: about 7 of 300
  CHECK(r1.failed == r2.failed);
  CHECK(t1.find("failed: runaway") != std::string::npos);
  const std::string summary = kneesim::io::read_file(a / "summary.json");
  CHECK(summary.find("\"trials_failed\": " + std::to_string(r1.failed)) != std::string::npos);
  CHECK(summary.find("\"n\": " + std::to_string(300 - r1.failed)) != std::string::npos);
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST_CASE("a study stopped mid-way and resumed loses and repeats nothing") {
  const s::StudyProblem base = linear_problem(0.0, {1, 1}, {1, 1});
  const fs::path whole = temp_dir("whole"), part = temp_dir("part");
  s::run_study(base, options(whole, s::Method::kLatinHypercube, 60), ranks());

  // the first launch stops (as if killed) after 25 evaluations: its journal keeps them
  s::StudyProblem stopping = base;
  auto count = std::make_shared<std::atomic<int>>(0);
  stopping.evaluate = [base, count](const std::vector<double>& x) {
    if (++*count > 25 + 1) throw kneesim::InputError("killed");  // +1: the nominal trial
    return base.evaluate(x);
  };
  CHECK_THROWS(s::run_study(stopping, options(part, s::Method::kLatinHypercube, 60), ranks()));
  CHECK_FALSE(fs::exists(part / "trials.csv"));
  // a torn last line, as a kill during a write leaves it, is dropped and its trial redone
  {
    std::ofstream j(s::journal_path(part, 0), std::ios::app);
    j << "T 59 123 - ok - 2 0x1p+0";
  }
  auto evaluations = std::make_shared<std::atomic<int>>(0);
  s::StudyProblem counting = base;
  counting.evaluate = [base, evaluations](const std::vector<double>& x) {
    ++*evaluations;
    return base.evaluate(x);
  };
  s::StudyOptions o = options(part, s::Method::kLatinHypercube, 60);
  o.resume = true;
  const auto r = s::run_study(counting, o, ranks());
  CHECK(r.resumed + r.computed == 60);
  CHECK(r.resumed >= 24);  // the stop can catch up to one trial per thread in flight
  CHECK(*evaluations == r.computed + 1);  // + the nominal trial
  CHECK(kneesim::io::read_file(part / "trials.csv") == kneesim::io::read_file(whole / "trials.csv"));

  // a journal of another study is refused
  s::run_study(base, options(part, s::Method::kLatinHypercube, 60), ranks());
  {
    std::ofstream j(s::journal_path(part, 0));
    j << s::journal_header(99);
  }
  CHECK_THROWS_WITH_AS(s::run_study(base, o, ranks()), doctest::Contains("different study"),
                       kneesim::InputError);
  fs::remove_all(whole);
  fs::remove_all(part);
}
