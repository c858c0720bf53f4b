// Small pure rotation kernels: the SO(3) exponential map used by the explicit integrator and
// the gimbal decomposition R = Rz(fe) * Rx(vv) * Ry(ie) that defines the carriage DOFs.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace kneesim::engine {

// exp([w]x) for a rotation vector w [rad] (Rodrigues), exact to round-off
inline Eigen::Matrix3d so3_exp(const Eigen::Vector3d& w) {
  const double theta2 = w.squaredNorm();
  Eigen::Matrix3d W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  double a, b;
  if (theta2 < 1e-16) {
    // series: sin(t)/t ~ 1 - t^2/6, (1 - cos t)/t^2 ~ 1/2 - t^2/24
    a = 1.0 - theta2 / 6.0;
    b = 0.5 - theta2 / 24.0;
  } else {
    const double theta = std::sqrt(theta2);
    a = std::sin(theta) / theta;
    b = (1.0 - std::cos(theta)) / theta2;
  }
  return Eigen::Matrix3d::Identity() + a * W + b * W * W;
}

// left-multiplicative update with a world-frame angular velocity: R <- exp(dt w) R
inline Eigen::Matrix3d update_rotation(const Eigen::Matrix3d& R, const Eigen::Vector3d& w_W,
                                       double dt) {
  return so3_exp(dt * w_W) * R;
}

struct GimbalAngles {
  double vv = 0.0;  // about x [rad]
  double ie = 0.0;  // about y [rad]
  double fe = 0.0;  // about z [rad]
};

inline Eigen::Matrix3d gimbal_rotation(const GimbalAngles& g) {
  const double ca = std::cos(g.fe), sa = std::sin(g.fe);
  const double cb = std::cos(g.vv), sb = std::sin(g.vv);
  const double cc = std::cos(g.ie), sc = std::sin(g.ie);
  Eigen::Matrix3d Rz, Rx, Ry;
  Rz << ca, -sa, 0, sa, ca, 0, 0, 0, 1;
  Rx << 1, 0, 0, 0, cb, -sb, 0, sb, cb;
  Ry << cc, 0, sc, 0, 1, 0, -sc, 0, cc;
  return Rz * Rx * Ry;
}

// inverse of gimbal_rotation for |vv| < 90 deg
inline GimbalAngles find_gimbal_angles(const Eigen::Matrix3d& R) {
  GimbalAngles g;
  g.vv = std::asin(std::clamp(R(2, 1), -1.0, 1.0));
  g.ie = std::atan2(-R(2, 0), R(2, 2));
  g.fe = std::atan2(-R(0, 1), R(1, 1));
  return g;
}

// world directions of the three gimbal axes (vv, ie, fe order): fe about z, vv about the
// floating x axis Rz x, ie about the body y axis Rz Rx y
inline void find_gimbal_axes(const GimbalAngles& g, Eigen::Vector3d& a_vv, Eigen::Vector3d& a_ie,
                             Eigen::Vector3d& a_fe) {
  const double ca = std::cos(g.fe), sa = std::sin(g.fe);
  const double cb = std::cos(g.vv), sb = std::sin(g.vv);
  a_fe = Eigen::Vector3d(0, 0, 1);
  a_vv = Eigen::Vector3d(ca, sa, 0);
  // Rz * Rx * (0,1,0) = Rz * (0, cb, sb)
  a_ie = Eigen::Vector3d(-sa * cb, ca * cb, sb);
}

}  // namespace kneesim::engine
