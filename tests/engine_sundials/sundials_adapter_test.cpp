// Tests of the SUNDIALS adapter against closed forms: a nonlinear system with a known root
// (KINSOL) and the harmonic oscillator y'' = -w^2 y (CVODE, BDF and Adams).
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "engine/sundials_adapter.h"

using kneesim::engine::NonlinearOptions;
using kneesim::engine::OdeIntegrator;
using kneesim::engine::OdeMethod;
using kneesim::engine::OdeOptions;
using kneesim::engine::Positivity;
using kneesim::engine::solve_nonlinear;

TEST_CASE("KINSOL finds the known root of a coupled nonlinear system") {
  // x^2 + y^2 = 5, x y = 2 has the root (2, 1) in the quadrant x > y > 0
  auto f = [](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    r[0] = x[0] * x[0] + x[1] * x[1] - 5.0;
    r[1] = x[0] * x[1] - 2.0;
  };
  const auto res = solve_nonlinear(f, Eigen::Vector2d(3.0, 0.5));
  CHECK(res.converged);
  CHECK(res.x[0] == doctest::Approx(2.0).epsilon(1e-10));
  CHECK(res.x[1] == doctest::Approx(1.0).epsilon(1e-10));
  CHECK(res.residual_norm <= 1e-10);
  CHECK(res.iterations > 0);
}

TEST_CASE("KINSOL honours positivity constraints and scaling") {
  // x^2 = 4 has roots +-2; starting near -1 with x > 0 enforced must give +2 (Newton
  // unconstrained would go to -2). Scaling: residual in units of 1e6.
  auto f = [](const Eigen::VectorXd& x, Eigen::VectorXd& r) { r[0] = 1e6 * (x[0] * x[0] - 4.0); };
  NonlinearOptions opt;
  opt.constraints = Eigen::VectorXi::Constant(1, static_cast<int>(Positivity::positive));
  opt.f_scale = Eigen::VectorXd::Constant(1, 1e-6);
  const auto res = solve_nonlinear(f, Eigen::VectorXd::Constant(1, 0.5), opt);
  CHECK(res.converged);
  CHECK(res.x[0] == doctest::Approx(2.0).epsilon(1e-10));
}

TEST_CASE("KINSOL reports failure on a system without a root") {
  auto f = [](const Eigen::VectorXd& x, Eigen::VectorXd& r) { r[0] = x[0] * x[0] + 1.0; };
  const auto res = solve_nonlinear(f, Eigen::VectorXd::Constant(1, 1.0));
  CHECK_FALSE(res.converged);
  CHECK_FALSE(res.message.empty());
}

TEST_CASE("a residual callback exception reaches the caller") {
  auto f = [](const Eigen::VectorXd&, Eigen::VectorXd&) { throw std::domain_error("boom"); };
  CHECK_THROWS_AS(solve_nonlinear(f, Eigen::VectorXd::Constant(1, 1.0)), std::domain_error);
}

TEST_CASE("CVODE integrates the harmonic oscillator to tolerance") {
  // y = (x, v), x'' = -w^2 x, x(0) = 1, v(0) = 0: x = cos(w t), v = -w sin(w t)
  const double w = 2.0 * M_PI;
  auto rhs = [w](double, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
    ydot[0] = y[1];
    ydot[1] = -w * w * y[0];
  };
  for (const OdeMethod method : {OdeMethod::bdf, OdeMethod::adams}) {
    OdeOptions opt;
    opt.method = method;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    OdeIntegrator ode(2, rhs, opt);
    ode.reset(0.0, Eigen::Vector2d(1.0, 0.0));
    Eigen::VectorXd y;
    double max_err = 0.0;
    for (int i = 1; i <= 50; ++i) {
      const double t = 0.1 * i;  // five periods
      ode.advance_to(t, y);
      max_err = std::max(max_err, std::abs(y[0] - std::cos(w * t)));
      max_err = std::max(max_err, std::abs(y[1] + w * std::sin(w * t)) / w);
    }
    CAPTURE(static_cast<int>(method));
    CHECK(max_err < 1e-6);
    CHECK(ode.num_rhs_evals() > 0);
    // energy invariant x^2 + (v/w)^2 = 1
    CHECK(y[0] * y[0] + y[1] * y[1] / (w * w) == doctest::Approx(1.0).epsilon(1e-6));
  }
}

TEST_CASE("CVODE reset restarts from a new state and max_step is honoured") {
  // y' = -y: y(t) = y0 exp(-(t - t0))
  auto rhs = [](double, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) { ydot = -y; };
  OdeOptions opt;
  opt.max_step = 0.01;
  OdeIntegrator ode(1, rhs, opt);
  Eigen::VectorXd y;
  ode.reset(0.0, Eigen::VectorXd::Constant(1, 1.0));
  ode.advance_to(1.0, y);
  CHECK(y[0] == doctest::Approx(std::exp(-1.0)).epsilon(1e-6).scale(0));
  CHECK(ode.num_steps() >= 100);  // 1 s at most 0.01 s per step
  ode.reset(2.0, Eigen::VectorXd::Constant(1, 3.0));
  ode.advance_to(2.5, y);
  CHECK(y[0] == doctest::Approx(3.0 * std::exp(-0.5)).epsilon(1e-6));
  CHECK(ode.time() == doctest::Approx(2.5));
}
