// SUNDIALS CVODE reference integrator (engine/reference_integrator.h) against the explicit
// central-difference integrator on the same coarse default model (3 mm insert edges), AP and
// IE traces over the last of two cycles. Reference: both solve m qdd = Q(q, qd, t) - c qd
// for the free and force-driven DOFs; CVODE (BDF, rtol 1e-7) is the accurate solution and the
// explicit scheme must agree within the bound below at the step the model chose. The explicit run's frames are the steps nearest each 1 % of the cycle
// (within dt/2), CVODE's are exact; that offset is part of the measured difference.
//
// Measured (this file's MESSAGE, 3 mm edges): AP 0.26 mm and IE 0.36 deg RMS, largest at the
// IE's release at 59 % (1.4 deg) and in swing (AP 1.0 mm at 84 %). The rig's light DOFs (AP,
// IE: engine/model.h) take their contact stiffness at the new position, a first-order
// scheme that lags a fast release by a few steps where CVODE follows the tiny inertias
// exactly; halving and quartering the step bring the RMS to 0.19 / 0.26 and 0.15 / 0.21.
// Where friction holds the joint (stick), each solver stops it where its own path left it,
// which keeps a floor of about 0.15 mm / 0.2 deg. The bound is 0.35 mm / 0.5 deg RMS (the
// issue-2 bound of 0.2 held for the heavy carriages of before, 2 kg and 0.01 kg m^2, whose
// inertia moved the ranges by 6 %: docs/validation.md#carriage-masses).
#include "integrator_agreement.h"

using namespace kneesim;

TEST_CASE("CVODE and central difference agree on AP and IE at the default settings") {
  const test::Agreement a = test::compare_integrators({"implant.edge_length_mm=3"}, 2);
  CHECK(a.ap_rms_mm < 0.35);
  CHECK(a.ie_rms_deg < 0.5);
}

TEST_CASE("CVODE stops a rig that runs away, as the explicit step does") {
  // no restraint, no friction and ten times the AP force: nothing holds the tibial carriage,
  // which slides off the insert within the first 0.1 s. Reference: the explicit step's runaway
  // check (50 mm / 60 deg from the start, engine/step.h find_runaway); the CVODE run must stop
  // with the same status instead of returning a range of motion of hundreds of mm as a result.
  models::BuiltModel built = models::build_model(test::default_config(
      {"implant.edge_length_mm=3", "rig.restraint.kind=none", "contact.friction=0",
       "gait.ap_force_scale=10", "contact.calibration=auto"}));
  engine::Model& model = built.model;
  engine::RunOptions options;
  options.cycles = 1;
  for (const engine::IntegratorKind kind :
       {engine::IntegratorKind::kCentralDifference, engine::IntegratorKind::kCvode}) {
    model.integrator = kind;
    engine::State s = engine::make_initial_state(model);
    engine::Data d = engine::make_data(model);
    const engine::RunResult r = engine::simulate(model, s, d, options);
    MESSAGE("integrator " << static_cast<int>(kind) << ": " << std::string(engine::to_string(r.status))
                          << " at t = " << r.failed_at << " s");
    CHECK(r.status == engine::StepStatus::kRunawayMotion);
    CHECK(r.failed_at > 0.0);
    CHECK(r.failed_at < 0.2 * model.period);
  }
}
