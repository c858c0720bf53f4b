// The stability monitor, the contact stiffness per DOF and the friction terms of the implicit
// friction (engine/contact.cpp sums them as second moments over the elements in contact and
// evaluates quadratic forms in the gimbal axes). Reference: their definitions, summed element
// by element at the same state from the per-element results calc_forces leaves in Data
// (data.h):
//  - tangent stiffness of translational DOF i: sum_e A_e dp/dd n_i^2; of rotational DOF i
//    about axis a: sum_e A_e dp/dd (a . (r x n))^2, r from the carriage's pivot;
//  - friction slope c_e (data.friction_viscosity) on the tangential part of the DOF's motion:
//    sum_e c_e |J_t|^2 with |J_t|^2 = 1 - n_i^2 or |a x r|^2 - (a . (r x n))^2;
//  - friction force on the DOF: J . (-c_e v_e) summed (v_e the element's slip, J = e_i or
//    a x r, the tibia's with the opposite sign), and its Coulomb bound: at least the sum of
//    mu p_e A_e |J_t| (the reduction's Cauchy-Schwarz bound), at most that of sqrt(n) times it;
//  - omega_max = max over the explicit free and force-driven DOFs of sqrt(K_i / m_i) (light,
//    implicit DOFs are stable for any step);
//  - the friction terms of a DOF neither free nor force-driven are zero (not used, not summed).
// Tolerance 1e-10 relative: the sums differ only in the order of rounding; a wrong term (a
// missing factor 2 of the off-diagonal moments, a swapped axis) is off by percents.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/contact_law.h"
#include "engine/step.h"
#include "engine_fixtures.h"

using namespace kneesim;

TEST_CASE("contact stiffness monitor and friction terms equal their per-element definitions") {
  const models::BuiltModel built =
      models::build_model(test::default_config({"implant.edge_length_mm=2"}));
  const engine::Model& model = built.model;
  engine::State state = engine::make_initial_state(model);
  engine::Data data = engine::make_data(model);
  // into stance (the load rises to its first peak near 13 % of the cycle) and swing
  int checked = 0;
  for (int i = 0; i < static_cast<int>(0.6 * model.period / model.dt); ++i) {
    REQUIRE(engine::step(model, state, data) == engine::StepStatus::kOk);
    if (i % 97 != 0) continue;
    engine::Data d = data;
    engine::calc_forces(model, state, d);
    REQUIRE(d.contact.elements_in_contact > 0);
    std::array<std::array<double, engine::kNumDof>, 2> stiffness{}, friction{}, force{}, bound{};
    for (int e : d.in_contact) {
      const Eigen::Vector3d c_W = d.X_WT * model.insert.centroid_T[e];
      const Eigen::Vector3d n_W = d.X_WT.linear() * model.insert.normal_T[e];
      const double ke = model.insert.area[e] *
                        engine::ef_stiffness(model.contact.law, model.contact.foundation_modulus, model.contact.exponent,
                                             d.penetration[e], model.insert.thickness[e]);
      const double ce = d.friction_viscosity[e];
      const Eigen::Vector3d slip_W = d.X_WT.linear() * d.slip_velocity_T[e];
      const Eigen::Vector3d f_W = -ce * slip_W;  // friction on the femur
      const double coulomb =
          ce * std::sqrt(slip_W.squaredNorm() +
                         model.contact.slip_regularization * model.contact.slip_regularization);
      for (int c = 0; c < 2; ++c) {
        const Eigen::Vector3d r = c_W - state.carriages[c].pivot_W;
        const double sign = c == 0 ? 1.0 : -1.0;
        for (int a = 0; a < 3; ++a) {
          const Eigen::Vector3d& axis = d.axes[c][a];
          const double j = axis.dot(r.cross(n_W));
          stiffness[c][a] += ke * n_W[a] * n_W[a];
          friction[c][a] += ce * (1.0 - n_W[a] * n_W[a]);
          force[c][a] += sign * f_W[a];
          bound[c][a] += coulomb * std::sqrt(std::max(0.0, 1.0 - n_W[a] * n_W[a]));
          stiffness[c][3 + a] += ke * j * j;
          const double jt2 = axis.cross(r).squaredNorm() - j * j;
          friction[c][3 + a] += ce * jt2;
          force[c][3 + a] += sign * axis.cross(r).dot(f_W);
          bound[c][3 + a] += coulomb * std::sqrt(std::max(0.0, jt2));
        }
      }
    }
    double omega_max = 0.0;
    for (int c = 0; c < 2; ++c) {
      for (int i = 0; i < engine::kNumDof; ++i) {
        const engine::DofModel& dof = model.carriages[c].dofs[i];
        if (dof.mode != engine::DofMode::kFree && dof.mode != engine::DofMode::kForce) {
          // the integrator does not read it; the reduction skips what only it would need
          CHECK(d.friction[c].secant[i] == 0.0);
          continue;
        }
        CHECK(d.friction[c].secant[i] == doctest::Approx(friction[c][i]).epsilon(1e-10).scale(0));
        CHECK(d.friction[c].force[i] ==
              doctest::Approx(force[c][i]).epsilon(1e-9).scale(1e-9 * bound[c][i]));
        CHECK(d.friction[c].capacity[i] >= bound[c][i] * (1.0 - 1e-10));
        CHECK(d.friction[c].capacity[i] <=
              bound[c][i] * std::sqrt(static_cast<double>(d.in_contact.size())) + 1e-12);
        CHECK(std::abs(d.friction[c].force[i]) <= d.friction[c].capacity[i] * (1.0 + 1e-10));
        CHECK(d.contact.stiffness[c][i] == doctest::Approx(stiffness[c][i]).epsilon(1e-10));
        if (dof.implicit) continue;
        omega_max = std::max(omega_max, std::sqrt(stiffness[c][i] / dof.mass));
      }
    }
    CHECK(d.contact.omega_max == doctest::Approx(omega_max).epsilon(1e-10));
    ++checked;
  }
  MESSAGE("stiffness monitor and friction terms checked at " << checked << " states");
  CHECK(checked >= 5);
}
