// The error-model kernels of the diagnosis (analysis/diagnosis/error_model.h) against closed
// forms: the Ornstein-Uhlenbeck whitening is the AR(1) innovation recursion
// e_1 = z_1, e_i = (z_i - phi z_{i-1}) / sqrt(1 - phi^2) with ln det C = sum ln(1 - phi_i^2);
// a random intercept has ln det(I + rho h h^T) = ln(1 + rho |h|^2) (matrix determinant lemma);
// the effective sample size of an equally spaced AR(1) series is
// 1 + (n - 1)(1 - phi)/(1 + phi); ridge least squares on one column is x^T r / (x^T x + lambda).
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "analysis/diagnosis/error_model.h"
#include "engine/errors.h"

using namespace kneesim::diagnosis;

TEST_CASE("OU whitening equals the AR(1) innovations at uneven spacing") {
  const std::vector<double> x = {0.0, 1.0, 2.5, 3.0, 5.0, 5.2};
  const int n = static_cast<int>(x.size());
  std::vector<int> series(static_cast<size_t>(n), 0);
  Eigen::VectorXd w = Eigen::VectorXd::Ones(n);
  CovarianceRows rows;
  rows.w = &w;
  rows.series = &series;
  rows.x = &x;
  const double ell = 1.7;
  std::vector<int> cluster(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) cluster[static_cast<size_t>(i)] = i;
  const Whitener wh({cluster}, rows, CovarianceParams{0.0, 0.0, ell});
  const Eigen::VectorXd z = Eigen::VectorXd::LinSpaced(n, 0.3, -1.1).array().sin();
  const Eigen::VectorXd e = wh.whiten(z);
  double log_det = 0.0;
  CHECK(e[0] == doctest::Approx(z[0]));
  for (int i = 1; i < n; ++i) {
    const double phi = std::exp(-(x[static_cast<size_t>(i)] - x[static_cast<size_t>(i - 1)]) / ell);
    CHECK(e[i] == doctest::Approx((z[i] - phi * z[i - 1]) / std::sqrt(1.0 - phi * phi)));
    log_det += std::log(1.0 - phi * phi);
  }
  CHECK(wh.log_det() == doctest::Approx(log_det));
  // colouring undoes whitening
  CHECK((wh.color(e) - z).norm() < 1e-12);
  // two series in one cluster do not correlate
  std::vector<int> two(static_cast<size_t>(n), 0);
  for (int i = 3; i < n; ++i) two[static_cast<size_t>(i)] = 1;
  rows.series = &two;
  const Whitener wh2({cluster}, rows, CovarianceParams{0.0, 0.0, ell});
  const Eigen::VectorXd e2 = wh2.whiten(z);
  CHECK(e2[3] == doctest::Approx(z[3]));
}

TEST_CASE("random slope and offset: determinant lemma and whitened norm") {
  Eigen::VectorXd w(4);
  w << 1.0, 2.0, 0.5, 1.5;
  Eigen::VectorXd dg(4);
  dg << 0.2, 0.4, 0.6, 0.8;
  std::vector<char> offset = {1, 1, 1, 0};
  std::vector<int> series = {0, 1, 2, 3};
  std::vector<double> x = {1, 2, 3, 4};
  CovarianceRows rows{&w, &dg, &offset, &series, &x};
  const double rho = 2.0, rho_o = 0.7;
  const Whitener wh({{0, 1, 2, 3}}, rows, CovarianceParams{rho, rho_o, 0.0});
  Eigen::VectorXd g = dg.cwiseProduct(w), h(4);
  h << w[0], w[1], w[2], 0.0;
  const Eigen::MatrixXd c =
      Eigen::MatrixXd::Identity(4, 4) + rho * g * g.transpose() + rho_o * h * h.transpose();
  CHECK(wh.log_det() == doctest::Approx(std::log(c.determinant())));
  const Eigen::VectorXd z = Eigen::Vector4d(0.3, -0.2, 0.5, 0.1);
  CHECK(wh.whiten(z).squaredNorm() == doctest::Approx(z.dot(c.inverse() * z)));
  // one parameter alone: ln(1 + rho |g|^2)
  const Whitener slope({{0, 1, 2, 3}}, rows, CovarianceParams{rho, 0.0, 0.0});
  CHECK(slope.log_det() == doctest::Approx(std::log1p(rho * g.squaredNorm())));
}

TEST_CASE("effective sample size of an AR(1) series") {
  const int n = 50;
  std::vector<int> series(n, 0);
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) x[static_cast<size_t>(i)] = i;
  const double ell = 4.0, phi = std::exp(-1.0 / ell);
  CHECK(effective_sample_size(series, x, ell) ==
        doctest::Approx(1.0 + (n - 1) * (1.0 - phi) / (1.0 + phi)));
  CHECK(effective_sample_size(series, x, 0.0) == doctest::Approx(n));
  // two independent series add
  for (int i = 25; i < n; ++i) series[static_cast<size_t>(i)] = 1;
  CHECK(effective_sample_size(series, x, ell) ==
        doctest::Approx(2.0 + (n - 2) * (1.0 - phi) / (1.0 + phi)));
}

TEST_CASE("nuisance terms: free columns are least squares, priored ones ridge") {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> z(0.0, 1.0);
  const int n = 30;
  Eigen::MatrixXd x(n, 2);
  Eigen::VectorXd r(n);
  for (int i = 0; i < n; ++i) x(i, 0) = 1.0, x(i, 1) = i / 10.0, r[i] = 0.5 + 0.2 * i / 10.0 + 0.1 * z(rng);
  Eigen::VectorXd resid;
  const Eigen::VectorXd free = solve_nuisance(r, x, Eigen::Vector2d(0.0, 0.0), &resid);
  const Eigen::VectorXd ols = (x.transpose() * x).ldlt().solve(x.transpose() * r);
  CHECK((free - ols).norm() < 1e-10);
  CHECK(std::abs((x.transpose() * resid).maxCoeff()) < 1e-9);  // residual orthogonal
  const double lambda = 7.0;
  const Eigen::VectorXd ridge = solve_nuisance(r, x.col(1), Eigen::VectorXd::Constant(1, lambda), nullptr);
  CHECK(ridge[0] == doctest::Approx(x.col(1).dot(r) / (x.col(1).squaredNorm() + lambda)));
  // a column that does not act on these rows gets 0, the other its least-squares value
  Eigen::MatrixXd x0 = x;
  x0.col(1).setZero();
  const Eigen::VectorXd b0 = solve_nuisance(r, x0, Eigen::Vector2d(0.0, 0.0), nullptr);
  CHECK(b0[1] == doctest::Approx(0.0));
  CHECK(b0[0] == doctest::Approx(r.mean()));
}

TEST_CASE("error-model names and keys: unknown ones are refused naming the allowed ones") {
  ErrorModel full;
  full.correlation = Correlation::ou;
  full.specimen_offset = true;
  full.nuisance.push_back({"gain", "a gain", 0.02, "gain_sd", nullptr});
  const ErrorModel white = select_error_model(full, "white", {}, "test");
  CHECK(white.correlation == Correlation::none);
  CHECK(white.nuisance.empty());
  CHECK_FALSE(white.specimen_offset);
  const ErrorModel corr = select_error_model(full, "correlated", {}, "test");
  CHECK(corr.correlation == Correlation::ou);
  CHECK(corr.nuisance.empty());
  const ErrorModel inst = select_error_model(full, "instrument", {{"gain_sd", 0.05}}, "test");
  REQUIRE(inst.nuisance.size() == 1);
  CHECK(inst.nuisance[0].prior_sd == 0.05);
  CHECK(select_error_model(full, "instrument", {{"ou", 0.0}}, "test").correlation ==
        Correlation::none);
  try {
    select_error_model(full, "pink", {}, "test");
    FAIL("an unknown model was accepted");
  } catch (const kneesim::InputError& e) {
    const std::string m = e.what();
    CHECK(m.find("--noise-model 'pink'") != std::string::npos);
    CHECK(m.find("white, correlated, instrument") != std::string::npos);
  }
  try {
    select_error_model(full, "instrument", {{"crosstalk", 0.1}}, "forces");
    FAIL("an unknown key was accepted");
  } catch (const kneesim::InputError& e) {
    const std::string m = e.what();
    CHECK(m.find("--noise-param 'crosstalk'") != std::string::npos);
    CHECK(m.find("forces error model") != std::string::npos);
    CHECK(m.find("gain_sd") != std::string::npos);
  }
  // a value outside its range is printed as given (-1, not std::to_string's -1.000000)
  try {
    select_error_model(full, "instrument", {{"gain_sd", -1.0}}, "forces");
    FAIL("a negative prior sd was accepted");
  } catch (const kneesim::InputError& e) {
    const std::string m = e.what();
    CHECK(m.find("--noise-param gain_sd = -1 is outside the allowed range [0, 1e6]") !=
          std::string::npos);
  }
}

TEST_CASE("a white part in a correlated series: determinant and effective sample size") {
  const std::vector<double> x = {0.0, 0.5, 1.5, 2.0, 3.5};
  std::vector<int> series(x.size(), 0);
  Eigen::VectorXd w = Eigen::VectorXd::Ones(5);
  CovarianceRows rows;
  rows.w = &w;
  rows.series = &series;
  rows.x = &x;
  const double ell = 1.3, nugget = 0.3;
  CovarianceParams p{0.0, 0.0, ell};
  p.nugget = nugget;
  const Whitener wh({{0, 1, 2, 3, 4}}, rows, p);
  Eigen::MatrixXd r(5, 5);
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      r(i, j) = i == j ? 1.0 : (1.0 - nugget) * std::exp(-std::abs(x[static_cast<size_t>(i)] - x[static_cast<size_t>(j)]) / ell);
    }
  }
  CHECK(wh.log_det() == doctest::Approx(std::log(r.determinant())));
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(5);
  CHECK(effective_sample_size(series, x, ell, nugget) == doctest::Approx(ones.dot(r.inverse() * ones)));
  // the information lies between the pure OU value and n
  CHECK(effective_sample_size(series, x, ell, nugget) > effective_sample_size(series, x, ell, 0.0));
  CHECK(effective_sample_size(series, x, ell, nugget) < 5.0);
}
