// The one adapter between kneesim and SUNDIALS 6.4 (design.md: each third-party library lives
// in one adapter file). It offers a KINSOL nonlinear solve and a CVODE ODE integrator on
// Eigen vectors with std::function callbacks, so no other file includes a SUNDIALS header.
//
// Design: every call owns its SUNContext and SUNDIALS objects (RAII inside the .cpp), which
// keeps the wrappers thread-safe when different threads use different objects. Callback
// exceptions are caught inside the C callbacks and rethrown after the solver returns (they
// must never unwind through C frames). Rejected: exposing N_Vector or the SUNDIALS flags in
// this header (it would leak the dependency into the engine and the wear models).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>

namespace kneesim::engine {

// F(x) = 0 residual; writes residual (same size as x)
using ResidualFn = std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& residual)>;

enum class Positivity {
  free,      // no constraint on x_i
  positive,  // x_i > 0
  non_negative,  // x_i >= 0
};

struct NonlinearOptions {
  double residual_tol = 1e-10;      // stop when max |F_i * f_scale_i| below this [residual units]
  double step_tol = 1e-14;          // scaled step tolerance [-]
  int max_iterations = 200;         // Newton iterations [-]
  bool line_search = true;          // globalise Newton with a line search
  Eigen::VectorXd x_scale;          // typical magnitude of x, (n) or empty for all ones [x units]
  Eigen::VectorXd f_scale;          // residual weights 1/typical |F|, (n) or empty for ones [1/F]
  Eigen::VectorXi constraints;      // (n) of Positivity values as int, or empty for none [-]
};

struct NonlinearResult {
  Eigen::VectorXd x;        // solution (or last iterate when not converged) [x units], (n)
  bool converged = false;   // max-norm of the scaled residual at x is within residual_tol
  long iterations = 0;      // Newton iterations taken [-]
  double residual_norm = 0.0;  // max-norm of the scaled residual at x [-]
  std::string message;      // empty on success, otherwise the KINSOL reason
};

// solves F(x) = 0 from x0 with KINSOL (Newton, dense finite-difference Jacobian)
NonlinearResult solve_nonlinear(const ResidualFn& residual, const Eigen::VectorXd& x0,
                                const NonlinearOptions& options = {});

// ydot = f(t, y)
using RhsFn =
    std::function<void(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot)>;

enum class OdeMethod {
  bdf,    // stiff problems (backward differentiation formulas, orders 1-5)
  adams,  // non-stiff problems (Adams-Moulton, orders 1-12)
};

struct OdeOptions {
  double rtol = 1e-8;        // relative tolerance [-]
  double atol = 1e-10;       // absolute tolerance [y units]
  OdeMethod method = OdeMethod::bdf;
  double max_step = 0.0;     // largest internal step, 0 for unlimited [s]
  long max_steps = 100000;   // internal steps allowed per advance_to call [-]
};

// CVODE integrator: reset(t0, y0) then advance_to(t, y) repeatedly with increasing t
class OdeIntegrator {
 public:
  OdeIntegrator(int n, RhsFn rhs, OdeOptions options = {});
  ~OdeIntegrator();
  OdeIntegrator(const OdeIntegrator&) = delete;
  OdeIntegrator& operator=(const OdeIntegrator&) = delete;

  void reset(double t0, const Eigen::VectorXd& y0);
  // integrates to t and writes y(t); throws std::runtime_error when CVODE fails
  void advance_to(double t, Eigen::VectorXd& y);
  long num_rhs_evals() const;
  long num_steps() const;
  double time() const;  // current solution time [s]

  struct Impl;  // SUNDIALS state, defined in the .cpp

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace kneesim::engine
