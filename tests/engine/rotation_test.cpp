// Rotation kernels (engine/rotation.h). References: the invariants of SO(3) (R^T R = I,
// det R = 1), Rodrigues' formula as implemented independently by Eigen::AngleAxisd, and the
// gimbal decomposition R = Rz(fe) Rx(vv) Ry(ie) (engine/model.h) and its inverse.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <random>

#include "engine/rotation.h"

using namespace kneesim::engine;

TEST_CASE("so3_exp matches Eigen::AngleAxisd") {
  // both are Rodrigues' formula; agreement to 1e-14 (a few ulps of entries of size 1),
  // including tiny angles where so3_exp switches to its series
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    Eigen::Vector3d axis(u(rng), u(rng), u(rng));
    axis.normalize();
    const double angle = (i % 4 == 0) ? 1e-9 * u(rng) : 3.0 * u(rng);
    const Eigen::Matrix3d a = so3_exp(angle * axis);
    const Eigen::Matrix3d b = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    worst = std::max(worst, (a - b).cwiseAbs().maxCoeff());
  }
  MESSAGE("so3_exp vs AngleAxisd: max entry difference " << worst);
  CHECK(worst < 1e-14);
  CHECK(so3_exp(Eigen::Vector3d::Zero()) == Eigen::Matrix3d::Identity());
}

TEST_CASE("update_rotation keeps R orthonormal over 1e5 random updates") {
  // the step updates R <- exp(dt w) R without re-orthonormalizing; round-off may accumulate
  // but must stay below 1e-12 after 1e5 updates of up to 0.1 rad (a typical 1 rad/s * 1e-4 s
  // step is 1e-4 rad; larger steps stress it more)
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 100000; ++i) {
    const Eigen::Vector3d w(u(rng), u(rng), u(rng));
    R = update_rotation(R, w, 0.1 * std::abs(u(rng)) / std::sqrt(3.0));
  }
  const double ortho = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  MESSAGE("after 1e5 updates: |R^T R - I| = " << ortho << ", det - 1 = " << R.determinant() - 1.0);
  CHECK(ortho < 1e-12);
  CHECK(std::abs(R.determinant() - 1.0) < 1e-12);
}

TEST_CASE("update_rotation integrates a constant angular velocity exactly") {
  // n steps of exp(dt w) compose to exp(n dt w) (rotations about one axis commute)
  const Eigen::Vector3d w(0.3, -1.2, 0.7);
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 1000; ++i) R = update_rotation(R, w, 1e-3);
  CHECK((R - so3_exp(w)).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("gimbal_rotation and find_gimbal_angles round-trip") {
  // exact inverse for |vv| < 90 deg: angles back to 1e-12 rad; the composition order is
  // Rz(fe) Rx(vv) Ry(ie), checked against Eigen's AngleAxis product; gimbal axes are the
  // columns d R / d angle R^T (world angular velocity per unit rate), checked by finite
  // differences (step 1e-6 rad, central: error O(1e-12))
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const GimbalAngles g{1.5 * u(rng), 3.1 * u(rng), 3.1 * u(rng)};
    const Eigen::Matrix3d R = gimbal_rotation(g);
    const Eigen::Matrix3d ref = (Eigen::AngleAxisd(g.fe, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(g.vv, Eigen::Vector3d::UnitX()) *
                                 Eigen::AngleAxisd(g.ie, Eigen::Vector3d::UnitY()))
                                    .toRotationMatrix();
    REQUIRE((R - ref).cwiseAbs().maxCoeff() < 1e-14);
    const GimbalAngles back = find_gimbal_angles(R);
    CHECK(std::abs(back.vv - g.vv) < 1e-12);
    CHECK(std::abs(back.ie - g.ie) < 1e-12);
    CHECK(std::abs(back.fe - g.fe) < 1e-12);

    Eigen::Vector3d axes[3];
    find_gimbal_axes(g, axes[0], axes[1], axes[2]);
    const double h = 1e-6;
    for (int a = 0; a < 3; ++a) {
      GimbalAngles gp = g, gm = g;
      double* pp[3] = {&gp.vv, &gp.ie, &gp.fe};
      double* pm[3] = {&gm.vv, &gm.ie, &gm.fe};
      *pp[a] += h;
      *pm[a] -= h;
      const Eigen::Matrix3d W =
          (gimbal_rotation(gp) - gimbal_rotation(gm)) / (2.0 * h) * R.transpose();
      const Eigen::Vector3d w(W(2, 1), W(0, 2), W(1, 0));
      CHECK((w - axes[a]).norm() < 1e-8);
    }
  }
}
