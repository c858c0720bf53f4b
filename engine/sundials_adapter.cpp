#include "engine/sundials_adapter.h"

#include <cvode/cvode.h>
#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>

namespace kneesim::engine {
namespace {

// owning handles: every SUNDIALS object is released in reverse order of creation
struct Context {
  SUNContext ctx = nullptr;
  Context() {
    if (SUNContext_Create(nullptr, &ctx) != 0) throw std::runtime_error("SUNContext_Create failed");
  }
  ~Context() { SUNContext_Free(&ctx); }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
};

struct Vector {
  N_Vector v = nullptr;
  Vector(sunindextype n, SUNContext ctx) : v(N_VNew_Serial(n, ctx)) {
    if (!v) throw std::runtime_error("N_VNew_Serial failed");
  }
  ~Vector() { N_VDestroy(v); }
  Vector(const Vector&) = delete;
  Vector& operator=(const Vector&) = delete;
  double* data() { return N_VGetArrayPointer(v); }
};

Eigen::Map<Eigen::VectorXd> as_eigen(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

void fill(Vector& v, const Eigen::VectorXd& x, double fallback) {
  const Eigen::Index n = N_VGetLength(v.v);
  for (Eigen::Index i = 0; i < n; ++i) v.data()[i] = (x.size() == n) ? x[i] : fallback;
}

// silences SUNDIALS' stderr printing; the message is kept for the result
void capture_error(int, const char*, const char*, char* msg, void* user) {
  if (user && msg) *static_cast<std::string*>(user) = msg;
}

struct KinUser {
  const ResidualFn* fn;
  Eigen::VectorXd x, f;  // scratch copies [x units], [F units]
  std::exception_ptr error;
  std::string message;
};

int kin_residual(N_Vector u, N_Vector fval, void* user_data) {
  auto* user = static_cast<KinUser*>(user_data);
  try {
    user->x = as_eigen(u);
    user->f.resize(user->x.size());
    (*user->fn)(user->x, user->f);
    as_eigen(fval) = user->f;
    return user->f.allFinite() ? 0 : 1;  // non-finite: recoverable, the line search backs off
  } catch (...) {
    user->error = std::current_exception();
    return -1;
  }
}

double scaled_max_norm(const ResidualFn& fn, const Eigen::VectorXd& x,
                       const Eigen::VectorXd& f_scale) {
  Eigen::VectorXd f(x.size());
  fn(x, f);
  if (f_scale.size() == f.size()) f = f.cwiseProduct(f_scale);
  return f.allFinite() ? f.cwiseAbs().maxCoeff() : INFINITY;
}

}  // namespace

NonlinearResult solve_nonlinear(const ResidualFn& residual, const Eigen::VectorXd& x0,
                                const NonlinearOptions& options) {
  const auto n = static_cast<sunindextype>(x0.size());
  Context c;
  Vector u(n, c.ctx), u_scale(n, c.ctx), f_scale(n, c.ctx), constraints(n, c.ctx);
  fill(u, x0, 0.0);
  // KINSOL scales by 1/typical magnitude
  for (sunindextype i = 0; i < n; ++i) {
    const double xs = (options.x_scale.size() == n) ? options.x_scale[i] : 1.0;
    u_scale.data()[i] = 1.0 / xs;
  }
  fill(f_scale, options.f_scale, 1.0);

  KinUser user{&residual, {}, {}, nullptr, {}};
  void* mem = KINCreate(c.ctx);
  if (!mem) throw std::runtime_error("KINCreate failed");
  SUNMatrix jac = SUNDenseMatrix(n, n, c.ctx);
  SUNLinearSolver ls = SUNLinSol_Dense(u.v, jac, c.ctx);
  KINSetErrHandlerFn(mem, capture_error, &user.message);
  KINInit(mem, kin_residual, u.v);
  KINSetUserData(mem, &user);
  KINSetLinearSolver(mem, ls, jac);
  KINSetFuncNormTol(mem, options.residual_tol);
  KINSetScaledStepTol(mem, options.step_tol);
  KINSetNumMaxIters(mem, options.max_iterations);
  KINSetMaxSetupCalls(mem, 1);  // fresh Jacobian every iteration: exact Newton on small systems
  if (options.constraints.size() == n) {
    for (sunindextype i = 0; i < n; ++i) {
      switch (static_cast<Positivity>(options.constraints[i])) {
        case Positivity::free: constraints.data()[i] = 0.0; break;
        case Positivity::positive: constraints.data()[i] = 2.0; break;
        case Positivity::non_negative: constraints.data()[i] = 1.0; break;
      }
    }
    KINSetConstraints(mem, constraints.v);
  }

  const int flag = KINSol(mem, u.v, options.line_search ? KIN_LINESEARCH : KIN_NONE, u_scale.v,
                          f_scale.v);
  NonlinearResult result;
  long iters = 0;
  KINGetNumNonlinSolvIters(mem, &iters);
  result.iterations = iters;
  result.x = as_eigen(u.v);
  KINFree(&mem);
  SUNLinSolFree(ls);
  SUNMatDestroy(jac);
  if (user.error) std::rethrow_exception(user.error);

  result.residual_norm = scaled_max_norm(residual, result.x, options.f_scale);
  // judged on the residual itself: at round-off level KINSOL's line search may report that it
  // cannot move (flag -5) although the iterate already meets the tolerance
  result.converged = result.residual_norm <= options.residual_tol;
  if (!result.converged) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " (flag %d, scaled residual %.3g after %ld iterations)", flag,
                  result.residual_norm, iters);
    result.message = (user.message.empty() ? std::string("KINSOL failed") : user.message) + buf;
  }
  return result;
}

struct OdeIntegrator::Impl {
  Context c;
  Vector y;
  RhsFn rhs;
  OdeOptions options;
  void* mem = nullptr;
  SUNMatrix jac = nullptr;
  SUNLinearSolver ls = nullptr;
  bool initialised = false;
  double t = 0.0;
  Eigen::VectorXd y_scratch, ydot_scratch;
  std::exception_ptr error;
  std::string message;

  Impl(int n, RhsFn f, OdeOptions o) : y(n, c.ctx), rhs(std::move(f)), options(o) {}
  ~Impl() {
    CVodeFree(&mem);
    SUNLinSolFree(ls);
    SUNMatDestroy(jac);
  }
};

namespace {

int cv_rhs(double t, N_Vector y, N_Vector ydot, void* user_data) {
  auto* impl = static_cast<OdeIntegrator::Impl*>(user_data);
  try {
    impl->y_scratch = as_eigen(y);
    impl->ydot_scratch.resize(impl->y_scratch.size());
    impl->rhs(t, impl->y_scratch, impl->ydot_scratch);
    as_eigen(ydot) = impl->ydot_scratch;
    return impl->ydot_scratch.allFinite() ? 0 : 1;  // non-finite: recoverable, smaller step
  } catch (...) {
    impl->error = std::current_exception();
    return -1;
  }
}

}  // namespace

OdeIntegrator::OdeIntegrator(int n, RhsFn rhs, OdeOptions options)
    : impl_(std::make_unique<Impl>(n, std::move(rhs), options)) {
  const int lmm = (options.method == OdeMethod::bdf) ? CV_BDF : CV_ADAMS;
  impl_->mem = CVodeCreate(lmm, impl_->c.ctx);
  if (!impl_->mem) throw std::runtime_error("CVodeCreate failed");
  impl_->jac = SUNDenseMatrix(n, n, impl_->c.ctx);
  impl_->ls = SUNLinSol_Dense(impl_->y.v, impl_->jac, impl_->c.ctx);
}

OdeIntegrator::~OdeIntegrator() = default;

void OdeIntegrator::reset(double t0, const Eigen::VectorXd& y0) {
  Impl& m = *impl_;
  if (y0.size() != N_VGetLength(m.y.v)) throw std::invalid_argument("OdeIntegrator::reset size");
  as_eigen(m.y.v) = y0;
  m.t = t0;
  if (m.initialised) {
    CVodeReInit(m.mem, t0, m.y.v);
    return;
  }
  CVodeSetErrHandlerFn(m.mem, capture_error, &m.message);
  CVodeInit(m.mem, cv_rhs, t0, m.y.v);
  CVodeSetUserData(m.mem, &m);
  CVodeSStolerances(m.mem, m.options.rtol, m.options.atol);
  CVodeSetLinearSolver(m.mem, m.ls, m.jac);
  CVodeSetMaxNumSteps(m.mem, m.options.max_steps);
  if (m.options.max_step > 0.0) CVodeSetMaxStep(m.mem, m.options.max_step);
  m.initialised = true;
}

void OdeIntegrator::advance_to(double t, Eigen::VectorXd& y) {
  Impl& m = *impl_;
  if (!m.initialised) throw std::logic_error("OdeIntegrator::advance_to before reset");
  if (t != m.t) {
    double t_reached = m.t;
    const int flag = CVode(m.mem, t, m.y.v, &t_reached, CV_NORMAL);
    if (m.error) {
      auto e = m.error;
      m.error = nullptr;
      std::rethrow_exception(e);
    }
    if (flag < 0) {
      throw std::runtime_error("CVODE failed at t = " + std::to_string(t_reached) + ": " +
                               (m.message.empty() ? "flag " + std::to_string(flag) : m.message));
    }
    m.t = t_reached;
  }
  y = as_eigen(m.y.v);
}

long OdeIntegrator::num_rhs_evals() const {
  long n = 0;
  if (impl_->initialised) CVodeGetNumRhsEvals(impl_->mem, &n);
  return n;
}

long OdeIntegrator::num_steps() const {
  long n = 0;
  if (impl_->initialised) CVodeGetNumSteps(impl_->mem, &n);
  return n;
}

double OdeIntegrator::time() const { return impl_->t; }

}  // namespace kneesim::engine
