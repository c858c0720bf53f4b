#include "engine/solid/hex8.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace kneesim::engine::solid {
namespace {

// dN_a/dxi_j at natural point (xi, eta, zeta)
Eigen::Matrix<double, kHexNodes, 3> natural_derivatives(double xi, double eta, double zeta) {
  Eigen::Matrix<double, kHexNodes, 3> d;
  for (int a = 0; a < kHexNodes; ++a) {
    const auto& n = kHexNatural[a];
    const double fx = 1.0 + n[0] * xi, fy = 1.0 + n[1] * eta, fz = 1.0 + n[2] * zeta;
    d(a, 0) = 0.125 * n[0] * fy * fz;
    d(a, 1) = 0.125 * n[1] * fx * fz;
    d(a, 2) = 0.125 * n[2] * fx * fy;
  }
  return d;
}

Eigen::Matrix3d jacobian(const HexPoints& x, const Eigen::Matrix<double, kHexNodes, 3>& dN) {
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();  // J_ij = dx_i / dxi_j
  for (int a = 0; a < kHexNodes; ++a) J += x[a] * dN.row(a);
  return J;
}

// natural-coordinate index sets of the four hourglass monomials: eta zeta, zeta xi, xi eta,
// xi eta zeta
constexpr std::array<std::array<int, 3>, kHourglassModes> kModeAxes = {
    {{1, 2, -1}, {2, 0, -1}, {0, 1, -1}, {0, 1, 2}}};

}  // namespace

std::array<double, kHexNodes> calc_corner_jacobians(const HexPoints& x) {
  std::array<double, kHexNodes> det{};
  for (int a = 0; a < kHexNodes; ++a) {
    const auto& n = kHexNatural[a];
    det[a] = jacobian(x, natural_derivatives(n[0], n[1], n[2])).determinant();
  }
  return det;
}

double calc_max_face_area(const HexPoints& x) {
  static constexpr int kFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                       {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  double area = 0.0;
  for (const auto& f : kFaces) {
    // a bilinear quadrilateral's area, half the norm of the cross product of its diagonals
    // (exact for planar faces)
    const Eigen::Vector3d d1 = x[f[2]] - x[f[0]], d2 = x[f[3]] - x[f[1]];
    area = std::max(area, 0.5 * d1.cross(d2).norm());
  }
  return area;
}

Hex8Reference make_hex8_reference(const HexPoints& X, double youngs_modulus,
                                  double shear_modulus) {
  Hex8Reference ref;
  // uniform gradient and volume by 2x2x2 Gauss quadrature: the integrands dN/dX det J (a
  // cofactor expression) and det J are polynomials of degree <= 3 per natural coordinate, so
  // the two-point rule is exact
  const double g = 1.0 / std::sqrt(3.0);
  ref.gradient.setZero();
  for (int i = 0; i < kHexNodes; ++i) {
    const auto& n = kHexNatural[i];
    const Eigen::Matrix<double, kHexNodes, 3> dN = natural_derivatives(g * n[0], g * n[1], g * n[2]);
    const Eigen::Matrix3d J = jacobian(X, dN);
    const double det = J.determinant();
    ref.volume += det;
    ref.gradient += dN * J.inverse() * det;  // dN/dX = dN/dxi J^-1
  }
  ref.gradient /= ref.volume;

  // Flanagan-Belytschko hourglass vectors
  for (int m = 0; m < kHourglassModes; ++m) {
    Eigen::Matrix<double, kHexNodes, 1> h;
    for (int a = 0; a < kHexNodes; ++a) {
      double v = 1.0;
      for (int k : kModeAxes[m])
        if (k >= 0) v *= kHexNatural[a][k];
      h[a] = v;
    }
    Eigen::Vector3d hX = Eigen::Vector3d::Zero();
    for (int a = 0; a < kHexNodes; ++a) hX += h[a] * X[a];
    for (int a = 0; a < kHexNodes; ++a) {
      ref.gamma(m, a) = 0.125 * (h[a] - hX.dot(ref.gradient.row(a).transpose()));
    }
  }

  // physical hourglass stiffness in the element's own frame (columns of the centre Jacobian,
  // orthonormalized; for a box element they are its edges)
  const Eigen::Matrix3d J0 = jacobian(X, natural_derivatives(0.0, 0.0, 0.0));
  Eigen::Vector3d L;
  for (int k = 0; k < 3; ++k) L[k] = 2.0 * J0.col(k).norm();
  const Eigen::Matrix3d R = Eigen::HouseholderQR<Eigen::Matrix3d>(J0).householderQ();
  Eigen::Matrix3d frame;  // unit axes of the element, signs following J0's columns
  for (int k = 0; k < 3; ++k) {
    frame.col(k) = R.col(k) * (R.col(k).dot(J0.col(k)) < 0.0 ? -1.0 : 1.0);
  }
  for (int m = 0; m < kHourglassModes; ++m) {
    const int order = kModeAxes[m][2] >= 0 ? 3 : 2;
    const double average = order == 2 ? 1.0 / 3.0 : 1.0 / 9.0;  // mean of the squared derivative
    Eigen::Vector3d k_local = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i) {
      bool i_in_mode = false;
      for (int k : kModeAxes[m]) i_in_mode |= (k == i);
      for (int k : kModeAxes[m]) {
        if (k < 0) continue;
        const double term = ref.volume * 4.0 / (L[k] * L[k]) * average;
        if (k == i) k_local[i] += youngs_modulus * term;
        else if (!i_in_mode) k_local[i] += shear_modulus * term;
      }
    }
    ref.hourglass_stiffness[m] = frame * k_local.asDiagonal() * frame.transpose();
  }

  for (int m = 0; m < kHourglassModes; ++m) {
    ref.hourglass_offset[m].setZero();
    for (int a = 0; a < kHexNodes; ++a) ref.hourglass_offset[m] += ref.gamma(m, a) * X[a];
  }
  ref.characteristic_length = ref.volume / calc_max_face_area(X);
  const auto det = calc_corner_jacobians(X);
  ref.min_jacobian = *std::min_element(det.begin(), det.end());
  return ref;
}

}  // namespace kneesim::engine::solid
