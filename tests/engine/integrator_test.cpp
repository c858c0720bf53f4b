// Central-difference integrator on a spring-mass (physics.md section 5), through engine::step:
// the tibial carriage's AP DOF is the only free DOF, restrained by one spring-gap element with
// gap 0 and the same stiffness k everywhere (a linear spring at the pivot), no insert
// elements, all other DOFs locked. References:
//  - the exact discrete recurrence of the velocity half-step scheme,
//      v(n+1/2) = v(n-1/2) - dt (k/m) x(n),  x(n+1) = x(n) + dt v(n+1/2),
//    equivalently x(n+1) = 2 x(n) - x(n-1) - (k dt^2 / m) x(n);
//  - the continuous solution x0 cos(omega t), omega = sqrt(k/m), to which the scheme converges
//    at second order (phase error omega^3 dt^2 t / 24);
//  - the stability limit dt = 2/omega: below it the scheme conserves the discrete energy
//    x(n)^2 + x(n-1)^2 - (2 - omega^2 dt^2) x(n) x(n-1); above it the amplitude grows by
//    |lambda| = |c/2 - sqrt(c^2/4 - 1)| per step, c = 2 - omega^2 dt^2.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "engine/simulate.h"
#include "engine/step.h"
#include "engine_fixtures.h"

namespace {

using namespace kneesim;

constexpr double kMass = 2.0;      // [kg]
constexpr double kStiff = 2.0e4;   // [N/m] -> omega = 100 rad/s
constexpr double kX0 = 1.0e-3;     // initial displacement [m]

double omega() { return std::sqrt(kStiff / kMass); }

engine::Model make_spring_mass(double dt) {
  engine::Model m = test::make_locked_model(dt);
  engine::DofModel& ap = m.carriages[1].dofs[0];
  ap.mode = engine::DofMode::kFree;
  ap.mass = kMass;
  ap.initial = kX0;
  engine::RestraintSpring s;
  s.kind = engine::RestraintKind::kTranslational;
  s.z_arm = 0.0;
  s.gap = 0.0;
  s.k_inside = s.k_positive = s.k_negative = kStiff;
  m.restraint.push_back(s);
  return m;
}

// runs up to n steps from x0 with the initial half-step rate v(-1/2) given (the standard
// central-difference start is v0 - dt/2 a0 = dt/2 omega^2 x0), returning x(0..) up to the
// first step that does not return kOk (whose status is put in *status when given)
std::vector<double> run_engine(double dt, int n, double v_half0,
                               engine::StepStatus* status = nullptr) {
  const engine::Model m = make_spring_mass(dt);
  engine::State s = engine::make_initial_state(m);
  engine::Data d = engine::make_data(m);
  s.carriages[1].rate[0] = v_half0;
  std::vector<double> x{s.carriages[1].pivot_W.x()};
  for (int i = 0; i < n; ++i) {
    const engine::StepStatus st = engine::step(m, s, d);
    x.push_back(s.carriages[1].pivot_W.x());
    if (st != engine::StepStatus::kOk) {
      if (status) *status = st;
      else REQUIRE(st == engine::StepStatus::kOk);
      break;
    }
  }
  return x;
}

double start_rate(double dt) { return 0.5 * dt * omega() * omega() * kX0; }

}  // namespace

TEST_CASE("central difference reproduces the discrete recurrence of a spring-mass") {
  const double dt = 1e-3;
  const int n = 2000;
  const std::vector<double> x = run_engine(dt, n, start_rate(dt));
  CHECK(x[0] == kX0);

  // velocity form, same operations as the scheme: expected bit for bit
  double xv = kX0, v = start_rate(dt);
  int bit_mismatches = 0;
  for (int i = 1; i <= n; ++i) {
    v += dt * (-(kStiff * xv)) / kMass;
    xv += dt * v;
    if (xv != x[i]) ++bit_mismatches;
  }
  CHECK(bit_mismatches == 0);

  // position-only recurrence x(n+1) = 2x(n) - x(n-1) - (k dt^2/m) x(n) with
  // x(-1) = x0 - dt v(-1/2): equal up to round-off (1e-12 of the amplitude over 2000 steps)
  double prev = kX0 - dt * start_rate(dt), cur = kX0, max_err = 0.0;
  const double c = kStiff * dt * dt / kMass;
  for (int i = 1; i <= n; ++i) {
    const double next = 2.0 * cur - prev - c * cur;
    prev = cur;
    cur = next;
    max_err = std::max(max_err, std::abs(cur - x[i]));
  }
  MESSAGE("spring-mass: max |engine - recurrence| = " << max_err / kX0 << " x0 over " << n
                                                      << " steps");
  CHECK(max_err < 1e-12 * kX0);
}

TEST_CASE("central difference converges to x0 cos(omega t) at second order") {
  // With the start v(-1/2) = dt/2 omega^2 x0, x(-1) = x0 (1 - omega^2 dt^2 / 2) = x0 cos(w_d dt),
  // so the discrete solution is exactly x(n) = x0 cos(w_d n dt), w_d = (2/dt) asin(omega dt/2)
  // = omega (1 + omega^2 dt^2 / 24 + ...): checked to 1e-9 x0 (round-off over 1000 steps).
  // Its distance to the continuous x0 cos(omega t) over t in [0, 0.5 s] (8 periods) is the
  // phase error, O(dt^2): it must drop by 4 when dt halves (3.7..4.3 allowed: the maximum is
  // taken over sampled times and the O(dt^4) terms).
  const double t_end = 0.5;
  double err[2];
  for (int k = 0; k < 2; ++k) {
    const double dt = 1e-3 / (1 << k);
    const int n = static_cast<int>(std::lround(t_end / dt));
    const std::vector<double> x = run_engine(dt, n, start_rate(dt));
    const double w_d = 2.0 / dt * std::asin(0.5 * omega() * dt);
    double e = 0.0, e_discrete = 0.0;
    for (int i = 0; i <= n; ++i) {
      e = std::max(e, std::abs(x[i] - kX0 * std::cos(omega() * i * dt)));
      e_discrete = std::max(e_discrete, std::abs(x[i] - kX0 * std::cos(w_d * i * dt)));
    }
    err[k] = e;
    const double predicted = kX0 * std::pow(omega(), 3) * dt * dt * t_end / 24.0;
    MESSAGE("dt = " << dt << " s: max |x - x0 cos(omega t)| = " << e / kX0
                    << " x0 (phase-error bound omega^3 dt^2 t/24 = " << predicted / kX0
                    << " x0); max |x - x0 cos(w_d t)| = " << e_discrete / kX0 << " x0");
    CHECK(e_discrete < 1e-9 * kX0);
    CHECK(e <= 1.01 * predicted);
    CHECK(e > 0.5 * predicted);
  }
  const double ratio = err[0] / err[1];
  MESSAGE("error ratio dt / (dt/2) = " << ratio);
  CHECK(ratio > 3.7);
  CHECK(ratio < 4.3);
}

TEST_CASE("spring-mass is stable just below dt = 2/omega and unstable just above") {
  const double dt_crit = 2.0 / omega();
  SUBCASE("0.99 dt_crit: the discrete energy is conserved, amplitude bounded") {
    const double dt = 0.99 * dt_crit;
    const int n = 20000;
    const std::vector<double> x = run_engine(dt, n, start_rate(dt));
    const double c = 2.0 - omega() * omega() * dt * dt;
    auto energy = [&](int i) { return x[i] * x[i] + x[i - 1] * x[i - 1] - c * x[i] * x[i - 1]; };
    const double e0 = energy(1);
    double worst = 0.0, amp = 0.0;
    for (int i = 1; i <= n; ++i) {
      worst = std::max(worst, std::abs(energy(i) - e0) / e0);
      amp = std::max(amp, std::abs(x[i]));
    }
    // bound of |x| on the invariant ellipse: sqrt(E / (1 - c^2/4))
    const double bound = std::sqrt(e0 / (1.0 - 0.25 * c * c));
    MESSAGE("0.99 dt_crit: energy drift " << worst << ", max |x| " << amp / kX0
                                          << " x0, invariant bound " << bound / kX0 << " x0");
    CHECK(worst < 1e-9);
    CHECK(amp <= bound * (1.0 + 1e-9));
  }
  SUBCASE("1.01 dt_crit: the amplitude grows by |lambda| per step until the runaway check") {
    // the engine stops the run with kRunawayMotion once the carriage is 50 mm from its start
    // (from x0 = 1 mm at |lambda| = 1.33 per step: after a few tens of steps)
    const double dt = 1.01 * dt_crit;
    engine::StepStatus status = engine::StepStatus::kOk;
    const std::vector<double> x = run_engine(dt, 1000, start_rate(dt), &status);
    const size_t n = x.size() - 1;
    const double c = 2.0 - omega() * omega() * dt * dt;
    const double lambda = std::abs(0.5 * c - std::sqrt(0.25 * c * c - 1.0));
    const double growth = std::abs(x[n] / x[n - 1]);
    MESSAGE("1.01 dt_crit: growth per step " << growth << ", closed form " << lambda
                                             << "; stopped after " << n << " steps at |x| = "
                                             << std::abs(x[n]) * 1e3 << " mm");
    CHECK(status == engine::StepStatus::kRunawayMotion);
    CHECK(n < 1000);
    CHECK(std::abs(x[n]) > 0.05);
    CHECK(growth == doctest::Approx(lambda).epsilon(1e-3));
  }
}

TEST_CASE("carriage damping: the free DOF decays as the damped recurrence") {
  // v(n+1/2) = v(n-1/2) + dt (-k x(n) - c v(n-1/2)) / m; the energy must decay monotonically
  // in the mean and the engine must match this recurrence bit for bit
  const double dt = 1e-3, c = 20.0;  // damping ratio c / (2 m omega) = 0.05
  engine::Model m = make_spring_mass(dt);
  m.carriages[1].dofs[0].damping = c;
  engine::State s = engine::make_initial_state(m);
  engine::Data d = engine::make_data(m);
  double xv = kX0, v = 0.0;
  int mismatches = 0;
  for (int i = 0; i < 1000; ++i) {
    REQUIRE(engine::step(m, s, d) == engine::StepStatus::kOk);
    v += dt * (-(kStiff * xv) - c * v) / kMass;
    xv += dt * v;
    if (xv != s.carriages[1].pivot_W.x()) ++mismatches;
  }
  CHECK(mismatches == 0);
  // after 1 s the envelope is about exp(-zeta omega t) = exp(-5) of x0 (zeta = 0.05); the
  // largest |x| over the last period must be within 10 % of it
  double last_peak = 0.0;
  for (int i = 0; i < 63; ++i) {
    REQUIRE(engine::step(m, s, d) == engine::StepStatus::kOk);
    last_peak = std::max(last_peak, std::abs(s.carriages[1].pivot_W.x()));
  }
  // the scheme's amplitude decays by sqrt(1 - c dt / m) per step (the product of the roots of
  // its characteristic polynomial), i.e. by exp(-c t / (2 m)) as the continuous solution: the
  // peak of the window lies between the envelope at its start (1 s) and at its end
  const double env_start = std::exp(-0.05 * omega() * 1.0) * kX0;
  const double env_end = std::exp(-0.05 * omega() * s.time) * kX0;
  MESSAGE("damped spring-mass: peak over [1, " << s.time << "] s " << last_peak / kX0
          << " x0, envelope " << env_start / kX0 << " .. " << env_end / kX0 << " x0");
  CHECK(last_peak <= 1.01 * env_start);
  CHECK(last_peak >= env_end);
}

TEST_CASE("a NaN force stops the run cleanly with kNotFinite") {
  // a restraint stiffness of NaN makes the first step's state NaN: step() reports it without
  // throwing, and simulate() stops at once, keeping the status and the failure time
  engine::Model m = make_spring_mass(1e-3);
  m.restraint[0].k_positive = std::numeric_limits<double>::quiet_NaN();
  engine::State s = engine::make_initial_state(m);
  engine::Data d = engine::make_data(m);
  CHECK(engine::step(m, s, d) == engine::StepStatus::kNotFinite);
  engine::State s2 = engine::make_initial_state(m);
  engine::Data d2 = engine::make_data(m);
  const engine::RunResult r = engine::simulate(m, s2, d2, engine::RunOptions{});
  CHECK(r.status == engine::StepStatus::kNotFinite);
  CHECK(r.failed_at == doctest::Approx(1e-3).scale(0));
  CHECK(r.steps == 1);
  CHECK(std::string(engine::to_string(r.status)).find("NaN") != std::string::npos);
}
