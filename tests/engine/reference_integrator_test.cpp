// SUNDIALS CVODE reference integrator (engine/reference_integrator.h) against the explicit
// central-difference integrator on the same coarse default model (3 mm insert edges), AP and
// IE traces over the last of two cycles. Reference: both solve m qdd = Q(q, qd, t) - c qd
// for the free and force-driven DOFs; CVODE (BDF, rtol 1e-7) is the accurate solution and the
// explicit scheme must agree within the issue-2 bound, 0.2 mm and 0.2 deg RMS, at the step
// the model chose. The explicit run's frames are the steps nearest each 1 % of the cycle
// (within dt/2), CVODE's are exact; that offset is part of the measured difference.
//
// Measured (this file's MESSAGEs): at the default settings AP 0.17 mm and IE 0.28 deg RMS —
// the IE bound is NOT met. The cause is the regularized Coulomb friction: its slope
// mu N / eps (eps = 1 mm/s, N = 2600 N: 1.8e5 N s/m) is a damper that the explicit velocity
// update integrates stably only for dt < 2 m / (mu N / eps) ~ 2e-5 s, 20x below the step
// chosen from the contact stiffness, so the carriages chatter while the joint sticks. With
// friction off, or with eps = 20 mm/s (inside the step's stability), the integrators agree to
// 0.01 mm and 0.01 deg (second test case), which pins the cause.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "engine/simulate.h"
#include "engine_fixtures.h"

using namespace kneesim;

namespace {

struct Agreement {
  double ap_rms_mm = 0.0, ie_rms_deg = 0.0, ap_max_mm = 0.0, ie_max_deg = 0.0;
  double explicit_s = 0.0, cvode_s = 0.0;
  long explicit_steps = 0, cvode_steps = 0;
  int elements = 0;
};

Agreement compare_integrators(const std::vector<std::string>& sets) {
  models::BuiltModel built = models::build_model(test::default_config(sets));
  engine::Model& model = built.model;
  engine::RunOptions options;
  options.cycles = 2;
  auto run = [&](engine::IntegratorKind kind, double& seconds) {
    model.integrator = kind;
    engine::State s = engine::make_initial_state(model);
    engine::Data d = engine::make_data(model);
    const auto t0 = std::chrono::steady_clock::now();
    engine::RunResult r = engine::simulate(model, s, d, options);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  };
  Agreement a;
  a.elements = model.insert.size();
  const engine::RunResult ex = run(engine::IntegratorKind::kCentralDifference, a.explicit_s);
  const engine::RunResult cv = run(engine::IntegratorKind::kCvode, a.cvode_s);
  REQUIRE(ex.status == engine::StepStatus::kOk);
  REQUIRE(cv.status == engine::StepStatus::kOk);
  REQUIRE(ex.frames.size() == 100u);
  REQUIRE(cv.frames.size() == 100u);
  a.explicit_steps = ex.steps;
  a.cvode_steps = cv.steps;
  constexpr double kDeg = 180.0 / std::numbers::pi;
  double ap2 = 0.0, ie2 = 0.0;
  for (size_t i = 0; i < ex.frames.size(); ++i) {
    const engine::Frame& e = ex.frames[i];
    const engine::Frame& c = cv.frames[i];
    CHECK(std::abs(std::remainder(e.gait_pct - c.gait_pct, 100.0)) <=
          50.0 * model.dt / model.period + 1e-9);
    const double dap = (e.q[1][0] - c.q[1][0]) * 1e3, die = (e.q[1][4] - c.q[1][4]) * kDeg;
    ap2 += dap * dap;
    ie2 += die * die;
    a.ap_max_mm = std::max(a.ap_max_mm, std::abs(dap));
    a.ie_max_deg = std::max(a.ie_max_deg, std::abs(die));
  }
  a.ap_rms_mm = std::sqrt(ap2 / ex.frames.size());
  a.ie_rms_deg = std::sqrt(ie2 / ex.frames.size());
  MESSAGE("CVODE vs central difference (" << sets.back() << ", " << a.elements
          << " elements): AP RMS " << a.ap_rms_mm << " mm (max " << a.ap_max_mm << "), IE RMS "
          << a.ie_rms_deg << " deg (max " << a.ie_max_deg << "); explicit " << a.explicit_s
          << " s (" << a.explicit_steps << " steps), CVODE " << a.cvode_s << " s ("
          << a.cvode_steps << " steps), CPU ratio explicit/CVODE " << a.explicit_s / a.cvode_s);
  return a;
}

}  // namespace

TEST_CASE("CVODE and central difference agree on AP and IE at the default settings") {
  const Agreement a = compare_integrators({"implant.edge_length_mm=3"});
  CHECK(a.ap_rms_mm < 0.2);
  CHECK(a.ie_rms_deg < 0.2);
}

TEST_CASE("CVODE and central difference agree closely when friction is inside the stable step") {
  // eps = 20 mm/s: mu N dt / (m eps) = 0.07 * 2600 * 4.4e-4 / (2 * 0.02) = 2.0 at peak load,
  // at the edge of the explicit damper limit; agreement then must be 10x inside the bound
  const Agreement a =
      compare_integrators({"implant.edge_length_mm=3", "contact.friction_regularization_mm_per_s=20"});
  CHECK(a.ap_rms_mm < 0.02);
  CHECK(a.ie_rms_deg < 0.02);
}
