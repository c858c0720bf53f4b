// The coupled rig step (engine/rig_coupling.h). References:
//  - without friction the Gauss-Seidel solution equals the dense solve of the same linear
//    system (Eigen LDLT) to 1e-10;
//  - with friction every row's equation a x + sum off x = b + clamp(F - c x, -Phi, Phi) holds
//    (residual below 1e-9 of the row's scale), and a single row is the one-DOF closed form
//    of engine/implicit_friction.h;
//  - the contact's coupled tangent stiffness is the derivative of the generalized contact
//    forces: central finite differences of calc_forces over each moved DOF, at rest (no damper,
//    no friction), on the built-in implant under a 1000 N load, within 3 % of the geometric
//    mean of the two diagonal entries (the geometric stiffness of the rotations, f x dr, is
//    left out: about 0.3 % of the contact's). The femoral normal matters: the symmetric
//    estimate sum k (n.J)^2 of the stability monitor puts the tibial AP at 28 000 N/m where
//    the derivative is 49 000 (the surfaces do not conform away from the dish's lowest point);
//  - determinism: the same bits with 1 and 2 threads.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "engine/implicit_friction.h"
#include "engine/rig_coupling.h"
#include "engine/stable_step.h"
#include "engine/step.h"
#include "engine_fixtures.h"

using namespace kneesim;

namespace {

engine::CoupledSystem make_system(int n, unsigned seed) {
  // a diagonally weighted SPD matrix with strong off-diagonal coupling (contraction near 0.9,
  // as the AP-axial pair on a conforming dish)
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, n);
  unsigned s = seed;
  auto next = [&s] {
    s = s * 1664525u + 1013904223u;
    return static_cast<double>(s >> 8) / static_cast<double>(1u << 24) - 0.5;
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) B(i, j) = next();
  Eigen::MatrixXd A = B * B.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
  engine::CoupledSystem sys;
  sys.n = n;
  for (int i = 0; i < n; ++i) {
    sys.a[i] = A(i, i);
    sys.b[i] = next();
    for (int j = 0; j < n; ++j) {
      if (i != j) sys.off[12 * i + j] = A(i, j);
    }
  }
  return sys;
}

}  // namespace

TEST_CASE("coupled rig step: Gauss-Seidel equals the dense solve without friction") {
  for (int n : {1, 2, 5, 12}) {
    const engine::CoupledSystem sys = make_system(n, 17u + n);
    Eigen::MatrixXd A(n, n);
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) {
      b[i] = sys.b[i];
      for (int j = 0; j < n; ++j) A(i, j) = i == j ? sys.a[i] : sys.off[12 * i + j];
    }
    const Eigen::VectorXd expected = A.ldlt().solve(b);
    std::array<double, 12> x{};
    const int sweeps = engine::solve_coupled_system(sys, x, 1e-14, 100000);
    CAPTURE(n);
    CAPTURE(sweeps);
    CHECK(sweeps < 100000);
    for (int i = 0; i < n; ++i) CHECK(x[i] == doctest::Approx(expected[i]).epsilon(1e-10));
  }
}

TEST_CASE("coupled rig step: rows with friction satisfy their capped equations") {
  engine::CoupledSystem sys = make_system(5, 99u);
  // friction on three rows: one sliding on its secant line, one pushed past its cap, one
  // at rest below its cap
  sys.friction[0] = -0.2, sys.secant[0] = 3.0, sys.capacity[0] = 0.3;
  sys.friction[2] = 0.05, sys.secant[2] = 50.0, sys.capacity[2] = 0.06;
  sys.friction[4] = 0.0, sys.secant[4] = 1e4, sys.capacity[4] = 10.0;
  std::array<double, 12> x{};
  engine::solve_coupled_system(sys, x, 1e-15, 100000);
  for (int k = 0; k < sys.n; ++k) {
    double lhs = sys.a[k] * x[k];
    for (int l = 0; l < sys.n; ++l)
      if (l != k) lhs += sys.off[12 * k + l] * x[l];
    const double F =
        sys.secant[k] > 0.0
            ? std::clamp(sys.friction[k] - sys.secant[k] * x[k], -sys.capacity[k], sys.capacity[k])
            : sys.friction[k];
    CAPTURE(k);
    CHECK(std::abs(lhs - sys.b[k] - F) <= 1e-9 * (std::abs(sys.b[k]) + sys.a[k] * std::abs(x[k]) + 1.0));
  }
  // a single row: the one-DOF closed form
  engine::CoupledSystem one;
  one.n = 1;
  one.a[0] = 500.0, one.b[0] = 20.0, one.friction[0] = -5.0, one.secant[0] = 2000.0,
  one.capacity[0] = 8.0;
  std::array<double, 12> y{};
  engine::solve_coupled_system(one, y);
  CHECK(y[0] == engine::find_implicit_friction_rate(0.0, 500.0, 20.0, -5.0, 2000.0, 8.0));
}

TEST_CASE("coupled rig step: the contact's coupled stiffness is the derivative of its forces") {
  models::BuiltModel built = models::build_model(test::default_config(
      {"implant.edge_length_mm=2", "contact.friction=0", "contact.damping_ratio=0",
       "solver.rig_coupling=coupled"}));
  const engine::Model& model = built.model;
  REQUIRE(model.coupled_rig_step);
  const engine::CoupledDofs dofs = engine::find_coupled_dofs(model);
  REQUIRE(dofs.n >= 3);
  engine::State s0 = engine::make_initial_state(model);
  {
    engine::Data d = engine::make_data(model);
    engine::position_femur_statically(model, s0, d, 1000.0);  // a loaded, conforming patch
  }
  engine::Data d0 = engine::make_data(model);
  engine::calc_forces(model, s0, d0);
  REQUIRE(d0.contact.elements_in_contact > 20);
  auto generalized = [&](int slot, double delta) {
    engine::State s = s0;
    const int c = slot / 6, i = slot % 6;
    if (i < 3) {
      s.carriages[c].pivot_W[i] += delta;
    } else {
      const Eigen::Vector3d axis = d0.axes[c][i - 3].normalized();
      s.carriages[c].R_WB = Eigen::AngleAxisd(delta * d0.axes[c][i - 3].norm(), axis) *
                            s.carriages[c].R_WB;
    }
    engine::Data d = engine::make_data(model);
    engine::calc_forces(model, s, d);
    return d.generalized;
  };
  for (int l = 0; l < dofs.n; ++l) {
    const int j = dofs.slot[l];
    const double delta = j % 6 < 3 ? 2e-7 : 2e-6;
    const auto plus = generalized(j, delta), minus = generalized(j, -delta);
    for (int k = 0; k < dofs.n; ++k) {
      const int i = dofs.slot[k];
      const double fd = -(plus[i / 6][i % 6] - minus[i / 6][i % 6]) / (2.0 * delta);
      // the restraint's own stiffness on the tibial AP and IE is not in the contact's
      const double restraint = (i == j && i / 6 == 1) ? d0.restraint_stiffness[i % 6] : 0.0;
      const double K = d0.contact_coupling[12 * i + j];
      const double scale = std::sqrt(d0.contact_coupling[13 * i] * d0.contact_coupling[13 * j]);
      CAPTURE(i);
      CAPTURE(j);
      CAPTURE(K);
      CAPTURE(fd - restraint);
      CHECK(std::abs(K - (fd - restraint)) <= 0.03 * scale);
    }
    MESSAGE("slot " << j << ": coupled diagonal " << d0.contact_coupling[13 * j]
            << ", the monitor's symmetric estimate sum k (n.J)^2 "
            << d0.contact.stiffness[j / 6][j % 6]);
  }
}

TEST_CASE("coupled rig step: the friction's coupled slopes are the derivative of its forces") {
  // at rest the regularized friction is linear in the slip (slope c_e = mu p A / eps), so a
  // rate u_j of one DOF gives every DOF i the friction -sum_e c_e J_i,t . J_j,t u_j: the
  // friction at a small rate of each moved DOF in turn (0.1 % of eps) against the matrix,
  // and its diagonal against the per-DOF secant the partitioned step uses
  models::BuiltModel built = models::build_model(test::default_config(
      {"implant.edge_length_mm=2", "contact.damping_ratio=0", "solver.rig_coupling=coupled"}));
  const engine::Model& model = built.model;
  const engine::CoupledDofs dofs = engine::find_coupled_dofs(model);
  engine::State s0 = engine::make_initial_state(model);
  {
    engine::Data d = engine::make_data(model);
    engine::position_femur_statically(model, s0, d, 1000.0);
  }
  engine::Data d0 = engine::make_data(model);
  engine::calc_forces(model, s0, d0);
  const double eps = model.contact.slip_regularization;
  REQUIRE(eps > 0.0);
  for (int l = 0; l < dofs.n; ++l) {
    const int j = dofs.slot[l];
    engine::State s = s0;
    // a rotation's rate is scaled so the contact points move about as fast as a translation's
    const double rate = (j % 6 < 3 ? 1e-3 : 1e-3 / 0.03) * eps;
    s.carriages[j / 6].rate[j % 6] = rate;
    engine::Data d = engine::make_data(model);
    engine::calc_forces(model, s, d);
    for (int k = 0; k < dofs.n; ++k) {
      const int i = dofs.slot[k];
      const double slope = -d.friction[i / 6].force[i % 6] / rate;
      const double C = d0.friction_coupling[12 * i + j];
      const double scale = std::sqrt(d0.friction_coupling[13 * i] * d0.friction_coupling[13 * j]);
      CAPTURE(i);
      CAPTURE(j);
      CAPTURE(C);
      CAPTURE(slope);
      CHECK(std::abs(C - slope) <= 0.01 * scale);
    }
    CHECK(d0.friction_coupling[13 * j] ==
          doctest::Approx(d0.friction[j / 6].secant[j % 6]).epsilon(1e-9));
  }
}

TEST_CASE("coupled rig step: the same bits with 1 and 2 threads") {
  models::BuiltModel built = models::build_model(test::default_config(
      {"implant.edge_length_mm=1", "contact.sdf_spacing_mm=0.6", "solver.rig_coupling=coupled"}));
  engine::Model& model = built.model;
  const int steps = static_cast<int>(0.1 / model.dt);
  uint64_t hash[2];
  for (int t = 1; t <= 2; ++t) {
    model.threads = t;
    engine::State s = engine::make_initial_state(model);
    engine::Data d = engine::make_data(model);
    for (int i = 0; i < steps; ++i) REQUIRE(engine::step(model, s, d) == engine::StepStatus::kOk);
    hash[t - 1] = engine::hash_state(s);
  }
  CHECK(hash[0] == hash[1]);
}
