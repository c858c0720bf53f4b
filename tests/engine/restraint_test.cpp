// Spring-gap soft-tissue restraint of every rig preset (physics.md section 2), as built by
// models::build_model and applied by the engine (engine::calc_forces -> data.restraint_force,
// data.generalized). Reference: the table of physics.md section 2 —
//   stanmore (Pal 2008): gap 3 mm, anterior 4.75 N/mm, posterior 22.18 N/mm, no stiffness
//     inside, from four springs at +-35 mm (two per side, each half the stiffness);
//   materials_study: the study's four linear springs of 10.4 N/mm, 41.6 N/mm in AP (acting
//     when the tibial AP is freed), 0.30 N m/deg in IE, no gap;
//   iso (ISO 14243-1:2009-like, approx.): AP gap 2.5 mm, 9.3 N/mm inside, 44 N/mm beyond;
//     IE gap 6 deg, 0.13 N m/deg inside, 0.36 beyond;
//   displacement: no restraint (AP and IE prescribed).
// AP force F(x) of the whole restraint at IE = 0 is evaluated through the engine stage with
// the tibia displaced by x; continuity at +-gap is checked one nanometre either side.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "engine/step.h"
#include "engine_fixtures.h"

using namespace kneesim;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct Restraint {
  engine::Model model;
  // AP force [N] and IE torque [N m] of the restraint with the tibia at AP x [m], IE a [rad]
  Eigen::Vector2d at(double x, double a) const {
    engine::State s = engine::make_initial_state(model);
    s.carriages[1].pivot_W.x() = model.carriages[1].pivot0_W.x() + x;
    s.carriages[1].R_WB = engine::gimbal_rotation({0.0, a, 0.0});
    engine::Data d = engine::make_data(model);
    engine::calc_forces(model, s, d);
    return {d.restraint_force.x(), d.restraint_force.y()};
  }
};

// the preset's restraint on an otherwise empty rig (no insert: the restraint alone)
Restraint make_restraint(const std::string& preset) {
  const models::BuiltModel built = models::build_model(test::default_config(
      {"rig.preset=" + preset, "implant.edge_length_mm=4", "contact.sdf_spacing_mm=1"}));
  Restraint r{test::make_locked_model(1e-4)};
  r.model.restraint = built.model.restraint;
  r.model.carriages[1].pivot0_W = built.model.carriages[1].pivot0_W;
  return r;
}

}  // namespace

TEST_CASE("stanmore restraint: Pal 2008 spring-gap law") {
  const Restraint r = make_restraint("stanmore");
  // two spring elements at +-35 mm, each with half of the anterior and posterior stiffness
  CHECK(r.model.restraint.size() == 2u);
  CHECK(r.at(2.9e-3, 0.0).x() == 0.0);
  CHECK(r.at(-2.9e-3, 0.0).x() == 0.0);
  CHECK(r.at(4e-3, 0.0).x() == doctest::Approx(-4.75).epsilon(1e-9));
  CHECK(r.at(-5e-3, 0.0).x() == doctest::Approx(44.36).epsilon(1e-9));
  for (double g : {3e-3, -3e-3}) {
    CHECK(std::abs(r.at(g - 1e-9 * (g > 0 ? 1 : -1), 0.0).x() -
                   r.at(g + 1e-9 * (g > 0 ? 1 : -1), 0.0).x()) < 1e-4);
  }
  // IE from the springs at +-35 mm: at 10 deg internal each spring end moves 35 sin(10 deg)
  // = 6.08 mm, one anterior, one posterior: torque -(z k (z sin a - g) cos a) summed over the
  // pair with each spring carrying half of its side's stiffness
  const double a = 10.0 * kDeg, z = 35e-3, g = 3e-3;
  const double x = z * std::sin(a);
  const double expected =
      -(z * std::cos(a) * 0.5 * 4.75e3 * (x - g)) + (-z * std::cos(a)) * (0.5 * 22.18e3 * (x - g));
  MESSAGE("stanmore IE restraint at 10 deg: " << r.at(0.0, a).y() << " N m (expected "
                                              << expected << ")");
  CHECK(r.at(0.0, a).y() == doctest::Approx(expected).epsilon(1e-9).scale(0));
  CHECK(r.at(0.0, a).y() < 0.0);  // restoring
}

TEST_CASE("materials_study restraint: linear AP and IE springs") {
  const Restraint r = make_restraint("materials_study");
  for (double x : {-4e-3, -1e-3, 1e-3, 4e-3}) {
    CHECK(r.at(x, 0.0).x() == doctest::Approx(-4.0 * 10.4e3 * x).epsilon(1e-9));
  }
  CHECK(r.at(0.0, 5.0 * kDeg).y() == doctest::Approx(-0.30 * 5.0).epsilon(1e-9).scale(0));
  CHECK(r.at(0.0, -5.0 * kDeg).y() == doctest::Approx(0.30 * 5.0).epsilon(1e-9).scale(0));
}

TEST_CASE("iso restraint: stiffness inside and beyond the gap, continuous") {
  const Restraint r = make_restraint("iso");
  CHECK(r.at(1e-3, 0.0).x() == doctest::Approx(-9.3).epsilon(1e-9));
  CHECK(r.at(3.5e-3, 0.0).x() == doctest::Approx(-9.3 * 2.5 - 44.0).epsilon(1e-9));
  CHECK(r.at(-3.5e-3, 0.0).x() == doctest::Approx(9.3 * 2.5 + 44.0).epsilon(1e-9));
  CHECK(r.at(0.0, 3.0 * kDeg).y() == doctest::Approx(-0.13 * 3.0).epsilon(1e-9).scale(0));
  CHECK(r.at(0.0, 8.0 * kDeg).y() ==
        doctest::Approx(-(0.13 * 6.0 + 0.36 * 2.0)).epsilon(1e-9).scale(0));
  CHECK(r.at(0.0, -8.0 * kDeg).y() ==
        doctest::Approx(0.13 * 6.0 + 0.36 * 2.0).epsilon(1e-9).scale(0));
  CHECK(std::abs(r.at(2.5e-3 - 1e-9, 0.0).x() - r.at(2.5e-3 + 1e-9, 0.0).x()) < 1e-4);
  CHECK(std::abs(r.at(0.0, 6.0 * kDeg - 1e-9).y() - r.at(0.0, 6.0 * kDeg + 1e-9).y()) < 1e-6);
}

TEST_CASE("displacement preset has no restraint") {
  const Restraint r = make_restraint("displacement");
  CHECK(r.model.restraint.empty());
  CHECK(r.at(5e-3, 0.1).norm() == 0.0);
}
