// Joint coordinates of the tibia relative to the femur (engine/joint_coordinates.h).
// References: closed-form poses whose joint coordinates are known by construction (a pure
// flexion, a pure femoral AP translation, a pure tibial VV or IE about the insert centre), the
// invariance of relative coordinates under a common rigid motion of both parts, and the
// defining property of Grood-Suntay translations (moving the insert along its own long axis e3
// changes IS only, even when the axes are not orthogonal).
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

#include "engine/joint_coordinates.h"

using namespace kneesim::engine;

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;

Eigen::Isometry3d pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}
Eigen::Matrix3d rot(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}
}  // namespace

TEST_CASE("joint coordinates: flexion and tibial translation, closed form") {
  // femur flexed 30 deg about +z at (0, 0.046, 0); insert centre at (3, 0, -2) mm, unrotated
  const auto X_WF = pose(rot(30 * kDeg, Eigen::Vector3d::UnitZ()), {0, 0.046, 0});
  const auto X_WT = pose(Eigen::Matrix3d::Identity(), {0.003, 0, -0.002});
  const JointCoordinates j = calc_joint_coordinates(X_WF, X_WT);
  CHECK(j.flexion == doctest::Approx(30 * kDeg).epsilon(1e-12).scale(0));
  CHECK(std::abs(j.vv) < 1e-12);
  CHECK(std::abs(j.ie) < 1e-12);
  CHECK(j.ap == doctest::Approx(0.003).epsilon(1e-12).scale(0));
  CHECK(j.ml == doctest::Approx(-0.002).epsilon(1e-12).scale(0));
  CHECK(j.is == doctest::Approx(-0.046).epsilon(1e-12).scale(0));
}

TEST_CASE("joint coordinates: a femoral carriage moving anterior moves the tibia posterior") {
  // the materials_study rig frees femoral AP: the joint AP is the insert relative to the femur,
  // so a femur 4 mm anterior of a fixed insert is AP = -4 mm, not the carriage's +4 or 0
  const auto X_WF = pose(rot(10 * kDeg, Eigen::Vector3d::UnitZ()), {0.004, 0.046, 0});
  const auto X_WT = pose(Eigen::Matrix3d::Identity(), {0, 0, 0});
  const JointCoordinates j = calc_joint_coordinates(X_WF, X_WT);
  CHECK(j.ap == doctest::Approx(-0.004).epsilon(1e-12).scale(0));
  CHECK(std::abs(j.ml) < 1e-15);
}

TEST_CASE("joint coordinates: rotation signs (frames.h) for either carriage") {
  SUBCASE("tibial varus about +x is +VV, tibial internal about +y is +IE") {
    const auto X_WF = pose(Eigen::Matrix3d::Identity(), {0, 0.046, 0});
    const JointCoordinates a =
        calc_joint_coordinates(X_WF, pose(rot(3 * kDeg, Eigen::Vector3d::UnitX()), {0, 0, 0}));
    CHECK(a.vv == doctest::Approx(3 * kDeg).epsilon(1e-12).scale(0));
    const JointCoordinates b =
        calc_joint_coordinates(X_WF, pose(rot(7 * kDeg, Eigen::Vector3d::UnitY()), {0, 0, 0}));
    CHECK(b.ie == doctest::Approx(7 * kDeg).epsilon(1e-12).scale(0));
    CHECK(std::abs(b.vv) < 1e-12);
  }
  SUBCASE("a femur tilted about +x is the tibia tilted the other way: VV < 0") {
    const auto X_WF = pose(rot(2 * kDeg, Eigen::Vector3d::UnitX()), {0, 0.046, 0});
    const JointCoordinates j = calc_joint_coordinates(X_WF, Eigen::Isometry3d::Identity());
    CHECK(j.vv == doctest::Approx(-2 * kDeg).epsilon(1e-12).scale(0));
  }
}

TEST_CASE("joint coordinates are invariant under a common rigid motion of both parts") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst_angle = 0.0, worst_length = 0.0;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Matrix3d R_F = rot(0.6 * u(rng), Eigen::Vector3d::UnitZ()) *
                                rot(0.1 * u(rng), Eigen::Vector3d::UnitX());
    const Eigen::Matrix3d R_T = rot(0.1 * u(rng), Eigen::Vector3d::UnitX()) *
                                rot(0.3 * u(rng), Eigen::Vector3d::UnitY());
    const auto X_WF = pose(R_F, {0.01 * u(rng), 0.046 + 0.01 * u(rng), 0.01 * u(rng)});
    const auto X_WT = pose(R_T, {0.01 * u(rng), 0.01 * u(rng), 0.01 * u(rng)});
    const auto X_common = pose(rot(3.0 * u(rng), {u(rng), u(rng), u(rng)}),
                               {u(rng), u(rng), u(rng)});
    const JointCoordinates a = calc_joint_coordinates(X_WF, X_WT);
    const JointCoordinates b = calc_joint_coordinates(X_common * X_WF, X_common * X_WT);
    worst_angle = std::max({worst_angle, std::abs(a.flexion - b.flexion),
                            std::abs(a.vv - b.vv), std::abs(a.ie - b.ie)});
    worst_length = std::max({worst_length, std::abs(a.ap - b.ap), std::abs(a.ml - b.ml),
                             std::abs(a.is - b.is)});
  }
  MESSAGE("common motion: max change " << worst_angle << " rad, " << worst_length << " m");
  CHECK(worst_angle < 1e-12);
  CHECK(worst_length < 1e-12);  // coordinates of ~0.05 m after motions of ~1 m
}

TEST_CASE("joint coordinates: a shift along the tibial axis e3 changes IS only") {
  // Grood-Suntay translations are components on e1, e2, e3 (not orthogonal when VV != 0)
  const auto X_WF = pose(rot(20 * kDeg, Eigen::Vector3d::UnitZ()), {0.001, 0.046, 0.002});
  const Eigen::Matrix3d R_T = rot(5 * kDeg, Eigen::Vector3d::UnitX()) *
                              rot(-8 * kDeg, Eigen::Vector3d::UnitY());
  const Eigen::Vector3d p_T(0.002, 0.0, -0.003);
  const JointCoordinates a = calc_joint_coordinates(X_WF, pose(R_T, p_T));
  const JointCoordinates b =
      calc_joint_coordinates(X_WF, pose(R_T, p_T + 0.01 * R_T.col(1)));
  CHECK(std::abs(b.ap - a.ap) < 1e-14);
  CHECK(std::abs(b.ml - a.ml) < 1e-14);
  CHECK(b.is - a.is == doctest::Approx(0.01).epsilon(1e-12).scale(0));
  CHECK(a.vv == doctest::Approx(5 * kDeg).epsilon(1e-12).scale(0));
  CHECK(a.ie == doctest::Approx(-8 * kDeg).epsilon(1e-12).scale(0));
}
