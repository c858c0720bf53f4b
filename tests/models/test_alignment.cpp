// Alignment and rig inputs (Pal 2008's 13 variables) as config keys, each moving the geometry
// or the rig as its name says. References: the poses the keys define (closed form: a pure
// translation or a rotation about one named axis, frames.h conventions), the restraint and
// contact fields the existing keys map to (physics.md section 2), and, for the geometry reuse
// of the studies, bit-identity with a full build (same Model fields, same State hash after
// steps).
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "engine/kinematics.h"
#include "engine/state.h"
#include "engine/step.h"
#include "models/build_model.h"
#include "models/config.h"

namespace m = kneesim::models;
namespace e = kneesim::engine;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

m::Config config_with(const std::vector<std::string>& sets) {
  std::vector<m::Override> o;
  // a coarse insert keeps the builds quick; the keys act the same at any resolution
  o.push_back({"implant.edge_length_mm", "2.0"});
  for (const auto& s : sets) o.push_back(m::parse_override(s));
  return m::load_config("", o);
}

// pose of a carriage's part at the initial DOF values
Eigen::Isometry3d initial_pose(const m::BuiltModel& b, int carriage) {
  std::array<double, e::kNumDof> q{};
  for (int i = 0; i < e::kNumDof; ++i) q[i] = b.model.carriages[carriage].dofs[i].initial;
  return e::calc_part_pose(b.model.carriages[carriage], q);
}

// rotation angle [deg] and unit axis of R
std::pair<double, Eigen::Vector3d> angle_axis(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return {aa.angle() / kDeg, aa.axis()};
}

}  // namespace

TEST_CASE("zero alignment is the implant's own reference: identity femur, medial tibial pivot") {
  const m::BuiltModel b = m::build_model(config_with({}));
  CHECK(b.model.femur().X_BP.matrix().isIdentity(0.0));
  CHECK(b.model.tibia().X_BP.linear().isIdentity(0.0));
  CHECK(b.model.tibia().pivot0_W.isApprox(Eigen::Vector3d(0, 0, -5e-3), 1e-15));
  // the insert frame T sits at the world origin
  CHECK(initial_pose(b, 1).translation().norm() < 1e-15);
}

TEST_CASE("femoral FE axis AP and IS offsets move the axis relative to the component") {
  const m::BuiltModel b0 = m::build_model(config_with({}));
  const m::BuiltModel ap = m::build_model(config_with({"rig.alignment.femur_fe_axis_ap_mm=2"}));
  const m::BuiltModel is = m::build_model(config_with({"rig.alignment.femur_fe_axis_is_mm=1.5"}));
  // FE axis 2 mm anterior of the component's own axis = the component 2 mm posterior of it
  CHECK(ap.model.femur().X_BP.translation().isApprox(Eigen::Vector3d(-2e-3, 0, 0), 1e-14));
  CHECK(ap.model.femur().X_BP.linear().isIdentity(0.0));
  CHECK(is.model.femur().X_BP.translation().isApprox(Eigen::Vector3d(0, -1.5e-3, 0), 1e-14));
  // the component still rests on the insert under the heel-strike load: its frame F lands
  // where it did (static placement), the carriage's FE axis 1.5 mm higher
  const Eigen::Isometry3d F0 = initial_pose(b0, 0), F1 = initial_pose(is, 0);
  CHECK(std::abs(F1.translation().y() - F0.translation().y()) < 1e-6);
  const double axis0 = b0.model.femur().pivot0_W.y() + b0.model.femur().dofs[1].initial;
  const double axis1 = is.model.femur().pivot0_W.y() + is.model.femur().dofs[1].initial;
  CHECK(axis1 - axis0 == doctest::Approx(1.5e-3).epsilon(1e-3).scale(0));
}

TEST_CASE("tibial IE axis AP and ML offsets move the pivot, not the insert") {
  const m::BuiltModel ap = m::build_model(config_with({"rig.alignment.tibia_ie_axis_ap_mm=1.5"}));
  const m::BuiltModel ml = m::build_model(config_with({"rig.alignment.tibia_ie_axis_ml_mm=1"}));
  CHECK(ap.model.tibia().pivot0_W.isApprox(Eigen::Vector3d(1.5e-3, 0, -5e-3), 1e-14));
  // + lateral: from 5 mm medial to 4 mm medial
  CHECK(ml.model.tibia().pivot0_W.isApprox(Eigen::Vector3d(0, 0, -4e-3), 1e-14));
  CHECK(initial_pose(ap, 1).translation().norm() < 1e-15);
  CHECK(initial_pose(ml, 1).translation().norm() < 1e-15);
}

TEST_CASE("initial femoral FE and IE rotations turn the component about z and y; VV the DOF") {
  struct Case {
    const char* key;
    Eigen::Vector3d axis;
  };
  for (const Case& c : {Case{"femur_fe_deg", Eigen::Vector3d::UnitZ()},
                        Case{"femur_ie_deg", Eigen::Vector3d::UnitY()}}) {
    CAPTURE(c.key);
    const m::BuiltModel b =
        m::build_model(config_with({std::string("rig.alignment.") + c.key + "=2"}));
    const auto [angle, axis] = angle_axis(b.model.femur().X_BP.linear());
    CHECK(angle == doctest::Approx(2.0).epsilon(1e-12));
    CHECK(axis.isApprox(c.axis, 1e-12));
    CHECK(b.model.femur().X_BP.translation().norm() == 0.0);
  }
  // the femoral VV position (Pal's Fem_VV) is the locked femoral VV DOF's value: the component
  // turns about the carriage's x axis
  const m::BuiltModel vv = m::build_model(config_with({"rig.femur_vv_deg=2"}));
  const auto [angle, axis] = angle_axis(initial_pose(vv, 0).linear());
  CHECK(angle == doctest::Approx(2.0).epsilon(1e-12));
  CHECK(axis.isApprox(Eigen::Vector3d::UnitX(), 1e-12));
}

TEST_CASE("insert tilt is a posterior slope: the posterior rim goes down, the anterior up") {
  const m::BuiltModel b = m::build_model(config_with({"rig.alignment.insert_tilt_deg=3"}));
  const Eigen::Isometry3d X_WT = initial_pose(b, 1);
  const auto [angle, axis] = angle_axis(X_WT.linear());
  CHECK(angle == doctest::Approx(3.0).epsilon(1e-12));
  CHECK(axis.isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  const Eigen::Vector3d posterior(-0.02, 0.008, 0.0), anterior(0.02, 0.008, 0.0);  // T [m]
  CHECK((X_WT * posterior).y() ==
        doctest::Approx(-0.02 * std::sin(3 * kDeg) + 0.008 * std::cos(3 * kDeg)).scale(0));
  CHECK((X_WT * posterior).y() < 0.008);
  CHECK((X_WT * anterior).y() > 0.008);
  CHECK(X_WT.translation().norm() < 1e-15);  // about T's own origin
}

TEST_CASE("spring gap, spring stiffnesses, friction and wear factor reach the rig and contact") {
  const m::BuiltModel b = m::build_model(config_with(
      {"rig.restraint.gap_mm=3.5", "rig.restraint.k_anterior_N_per_mm=4.84",
       "rig.restraint.k_posterior_N_per_mm=22.27", "contact.friction=0.08",
       "material.wear_factor_mm3_per_Nmm=2.7e-10"}));
  REQUIRE(b.model.restraint.size() == 2);  // the stanmore springs at +-35 mm
  for (const auto& s : b.model.restraint) {
    CHECK(s.gap == doctest::Approx(3.5e-3).scale(0));
    CHECK(s.k_positive == doctest::Approx(0.5 * 4.84e3));   // anterior, half per side [N/m]
    CHECK(s.k_negative == doctest::Approx(0.5 * 22.27e3));  // posterior
  }
  CHECK(b.model.contact.friction == 0.08);
  CHECK(b.material.wear_factor_mm3_per_Nmm == 2.7e-10);
}

TEST_CASE("a model built on another's geometry equals a full build, bit for bit") {
  const m::BuiltModel nominal = m::build_model(config_with({}));
  const m::Config varied = config_with({"rig.alignment.insert_tilt_deg=1.2",
                                        "rig.alignment.femur_fe_axis_ap_mm=-0.7",
                                        "rig.restraint.gap_mm=2.6", "contact.friction=0.06"});
  const m::BuiltModel full = m::build_model(varied);
  const m::BuiltModel reused = m::build_model(varied, &nominal);
  CHECK(reused.sdf_seconds == 0.0);  // the fields were copied, not looked up or built
  CHECK(reused.model.dt == full.model.dt);
  CHECK(reused.model.dt_critical == full.model.dt_critical);
  for (int c = 0; c < 2; ++c) {
    CHECK(reused.model.carriages[c].X_BP.matrix() == full.model.carriages[c].X_BP.matrix());
    CHECK(reused.model.carriages[c].pivot0_W == full.model.carriages[c].pivot0_W);
    for (int i = 0; i < e::kNumDof; ++i)
      CHECK(reused.model.carriages[c].dofs[i].initial == full.model.carriages[c].dofs[i].initial);
  }
  auto hash_after = [](const m::BuiltModel& b) {
    e::State s = e::make_initial_state(b.model);
    e::Data d = e::make_data(b.model);
    for (int k = 0; k < 300; ++k) REQUIRE(e::step(b.model, s, d) == e::StepStatus::kOk);
    return e::hash_state(s);
  };
  CHECK(hash_after(reused) == hash_after(full));

  // a different geometry key falls back to the full build
  const m::Config finer = config_with({"implant.edge_length_mm=1.5"});
  const m::BuiltModel fallback = m::build_model(finer, &nominal);
  CHECK(fallback.model.insert.size() != nominal.model.insert.size());
}

TEST_CASE("find_number_key: value and allowed range of a number key, none for others") {
  const m::Config c = config_with({"rig.alignment.insert_tilt_deg=2"});
  const auto tilt = m::find_number_key(c, "rig.alignment.insert_tilt_deg");
  REQUIRE(tilt);
  CHECK(tilt->value == 2.0);
  CHECK(tilt->lo == -15.0);
  CHECK(tilt->hi == 15.0);
  const auto mu = m::find_number_key(c, "material.friction");
  REQUIRE(mu);
  CHECK(mu->lo == 0.0);
  CHECK(mu->hi == 1.0);
  CHECK_FALSE(m::find_number_key(c, "rig.preset"));
  CHECK_FALSE(m::find_number_key(c, "no.such_key"));
}
