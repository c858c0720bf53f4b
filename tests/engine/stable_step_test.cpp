// Stable time step of a built default model (engine/stable_step.h, physics.md section 5).
// References: the report's own closed forms (dt_critical = 2/omega_max (sqrt(1 + z^2) - z),
// omega_max^2 = K/m of the governing DOF, dt = safety * dt_critical, beta = 2 z / omega_max),
// and the contact tangent stiffness against a central finite difference of the contact force.
// (That the chosen step runs stably is shown by default_run_test.cpp; the scheme's limit
// 2/omega itself by integrator_test.cpp.)
#include <doctest/doctest.h>

#include <cmath>

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
  CHECK(r.dt == doctest::Approx(config.dt_safety * r.dt_critical).epsilon(1e-12));
  CHECK(m.dt_critical == r.dt_critical);
  CHECK(r.dt_critical ==
        doctest::Approx(2.0 / r.omega_max * (std::sqrt(1.0 + z * z) - z)).epsilon(1e-12));
  CHECK(r.damping_beta == doctest::Approx(2.0 * z / r.omega_max).epsilon(1e-12));
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
