// Stable time step of a built default model (engine/stable_step.h, physics.md section 5).
// References: the report's own closed forms (dt_critical = 2/omega_max (sqrt(1 + z^2) - z),
// omega_max^2 = K/m of the governing DOF, dt = safety * dt_critical, beta = 2 z / omega_max),
// and the contact tangent stiffness against a central finite difference of the contact force.
// Last, the step retry of engine::simulate_with_retry. (That the chosen step runs stably is
// shown by default_run_test.cpp; the scheme's limit 2/omega itself by integrator_test.cpp.)
#include <doctest/doctest.h>

#include <cmath>

#include "engine/simulate.h"
#include "engine/stable_step.h"
#include "engine/step.h"
#include "engine_fixtures.h"

using namespace kneesim;

TEST_CASE("calc_stable_time_step on the default model") {
  const models::Config config =
      test::default_config({"implant.edge_length_mm=3", "contact.sdf_spacing_mm=0.5"});
  const models::BuiltModel built = models::build_model(config);
  const engine::Model& m = built.model;
  const engine::StableStepReport& r = built.stable_step;
  const double z = config.contact_damping_ratio;

  MESSAGE("stable step: omega_max " << r.omega_max << " rad/s, stiffness " << r.stiffness_max
          << " (carriage " << r.governing_carriage << ", dof "
          << std::string(engine::kDofNames[r.governing_dof]) << "), dt_critical " << r.dt_critical * 1e6
          << " us, dt " << r.dt * 1e6 << " us, model dt " << m.dt * 1e6 << " us");
  // the chosen step is below the estimated limit by the safety factor
  CHECK(m.dt <= r.dt * (1.0 + 1e-12));
  CHECK(r.dt < r.dt_critical);
  CHECK(r.dt == doctest::Approx(config.dt_safety * r.dt_critical).epsilon(1e-12).scale(0));
  CHECK(m.dt_critical == r.dt_critical);
  CHECK(r.dt_critical ==
        doctest::Approx(2.0 / r.omega_max * (std::sqrt(1.0 + z * z) - z)).epsilon(1e-12).scale(0));
  CHECK(r.damping_beta == doctest::Approx(2.0 * z / r.omega_max).epsilon(1e-12).scale(0));
  // the governing DOF is reported and is one that moves (free or force-driven)
  REQUIRE((r.governing_carriage == 0 || r.governing_carriage == 1));
  REQUIRE(r.governing_dof >= 0);
  REQUIRE(r.governing_dof < engine::kNumDof);
  const engine::DofModel& g = m.carriages[r.governing_carriage].dofs[r.governing_dof];
  CHECK((g.mode == engine::DofMode::kFree || g.mode == engine::DofMode::kForce));
  CHECK(r.omega_max == doctest::Approx(std::sqrt(r.stiffness_max / g.mass)).epsilon(1e-12));
  // a contact this stiff makes the step sub-millisecond and far above the spring restraint's
  // (4 kg on ~1e7 N/m: omega ~ 1e3..1e4 rad/s)
  CHECK(r.omega_max > 1e3);
  CHECK(r.omega_max < 1e5);
}

TEST_CASE("contact tangent stiffness matches a finite difference of the contact force") {
  // femur IS DOF pressed statically to 2600 N at 0 deg flexion; K_is = -dF_y/dy_femur by a
  // central difference of +-0.1 um (the law is smooth; elements entering or leaving the
  // contact edge change F by far less than 1 %). The analytic stiffness ignores the rotation
  // of the normals, a second-order effect: tolerance 2 %.
  const models::BuiltModel built = models::build_model(
      test::default_config({"implant.edge_length_mm=2", "contact.sdf_spacing_mm=0.4"}));
  const engine::Model& m = built.model;
  engine::State s = engine::make_initial_state(m);
  engine::Data d = engine::make_data(m);
  const double f = engine::position_femur_statically(m, s, d, 2600.0);
  CHECK(f == doctest::Approx(2600.0).epsilon(1e-3));
  const auto k = engine::calc_contact_stiffness(m, s, d);
  auto force_at = [&](double dy) {
    engine::State t = s;
    t.carriages[0].pivot_W.y() += dy;
    engine::Data dd = engine::make_data(m);
    engine::calc_forces(m, t, dd);
    return dd.contact.force_W.y();
  };
  const double h = 1e-7;
  const double k_fd = -(force_at(h) - force_at(-h)) / (2.0 * h);
  MESSAGE("femur IS contact stiffness: analytic " << k[0][1] << " N/m, finite difference "
                                                  << k_fd << " N/m");
  CHECK(k[0][1] == doctest::Approx(k_fd).epsilon(0.02));
}

TEST_CASE("stable step of restraint springs alone: closed forms") {
  // no insert: the only stiffness is the restraint on the tibial carriage. Reference:
  // omega = sqrt(k / m) of each DOF, dt_critical = 2/omega_max (sqrt(1 + z^2) - z)
  engine::Model m = test::make_locked_model(1e-4);
  auto& tibia = m.carriages[1].dofs;
  tibia[0].mode = engine::DofMode::kFree;  // AP, 0.01 kg
  tibia[0].mass = 0.01;
  tibia[4].mode = engine::DofMode::kFree;  // IE, 1 kg m^2
  tibia[4].mass = 1.0;
  SUBCASE("rotational IE spring: governs IE only, not AP") {
    engine::RestraintSpring s;
    s.kind = engine::RestraintKind::kRotational;
    s.k_inside = s.k_positive = s.k_negative = 1e6;  // [N m/rad] -> omega 1000 rad/s
    m.restraint.push_back(s);
    const engine::StableStepReport r = engine::calc_stable_time_step(m, 100.0, {0.0}, 0.0, 0.8);
    CHECK(r.governing_carriage == 1);
    CHECK(r.governing_dof == 4);
    CHECK(r.omega_max == doctest::Approx(1000.0).epsilon(1e-12));
    CHECK(r.dt_critical == doctest::Approx(2e-3).epsilon(1e-12).scale(0));
  }
  SUBCASE("pair of AP springs at +-z: AP k1 + k2, IE (k1 + k2) z^2") {
    for (double z : {-0.04, 0.04}) {
      engine::RestraintSpring s;
      s.kind = engine::RestraintKind::kTranslational;
      s.z_arm = z;
      s.gap = 1e-3;
      s.k_inside = 0.0;
      s.k_positive = s.k_negative = 50.0;  // [N/m]: AP omega = sqrt(100 / 0.01) = 100 rad/s
      m.restraint.push_back(s);
    }
    tibia[4].mass = 1e-6;  // IE omega = sqrt(100 * 0.0016 / 1e-6) = 400 rad/s
    const double z = 0.3;
    const engine::StableStepReport r = engine::calc_stable_time_step(m, 100.0, {0.0}, z, 0.8);
    CHECK(r.governing_dof == 4);
    CHECK(r.omega_max == doctest::Approx(400.0).epsilon(1e-12));
    CHECK(r.dt_critical ==
          doctest::Approx(2.0 / 400.0 * (std::sqrt(1.0 + z * z) - z)).epsilon(1e-12).scale(0));
  }
}

TEST_CASE("simulate_with_retry: a step beyond the limit is shortened to the measured frequency") {
  // a step 3x the estimated limit trips the stability monitor (step.h: omega_max dt above the
  // central-difference limit); the retry repeats the cycle from the same start state with the
  // step the measured frequency allows. References: the retried run is bit-identical to a
  // plain simulate() with the step it reports (the retry changes nothing but the step), that
  // step is a whole number per period and at most dt_safety of the limit of the measured
  // frequency, and with no retries allowed the failure is returned as it is.
  const models::BuiltModel built =
      models::build_model(test::default_config({"implant.edge_length_mm=3"}));
  engine::Model too_long = built.model;
  too_long.dt = engine::find_whole_cycle_step(too_long, 3.0 * built.stable_step.dt_critical);
  engine::RunOptions ro;
  ro.cycles = 1;

  engine::Model no_retry = too_long;
  engine::State s0 = engine::make_initial_state(no_retry);
  const engine::RunResult failed = engine::simulate_with_retry(no_retry, s0, ro, 0.8, 0);
  REQUIRE(failed.status == engine::StepStatus::kUnstableStep);
  CHECK(failed.step_retries == 0);
  CHECK(no_retry.dt == too_long.dt);
  CHECK(s0.time == failed.failed_at);  // the state is that of the returned (failed) run

  engine::Model retried = too_long;
  engine::State s1 = engine::make_initial_state(retried);
  int attempts = 0;
  const engine::RunResult ok =
      engine::simulate_with_retry(retried, s1, ro, 0.8, 4, [&attempts] { ++attempts; });
  REQUIRE(ok.status == engine::StepStatus::kOk);
  CHECK(ok.step_retries >= 1);
  CHECK(attempts == ok.step_retries + 1);
  CHECK(retried.dt < too_long.dt);
  const double per_period = retried.period / retried.dt;
  CHECK(std::abs(per_period - std::round(per_period)) < 1e-9);
  CHECK(ok.max_stability_ratio < 1.0);

  engine::State s2 = engine::make_initial_state(retried);
  engine::Data d2 = engine::make_data(retried);
  const engine::RunResult plain = engine::simulate(retried, s2, d2, ro);
  REQUIRE(plain.status == engine::StepStatus::kOk);
  REQUIRE(plain.frames.size() == ok.frames.size());
  for (size_t i = 0; i < plain.frames.size(); ++i) {
    CHECK(plain.frames[i].joint.ap == ok.frames[i].joint.ap);
    CHECK(plain.frames[i].joint.ie == ok.frames[i].joint.ie);
  }
  CHECK(s1.time == s2.time);
  CHECK(s1.step == s2.step);
}
