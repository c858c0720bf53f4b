// Eight-node hexahedron with one-point (uniform-gradient) integration and physical hourglass
// stabilization, total Lagrangian (physics.md section 5, "deformable insert").
//
// Why this element: explicit dynamics pays per element update, and a fully integrated hex8
// costs eight times the stress evaluations and locks in bending and near incompressibility
// (UHMWPE nu 0.47). One point at the centre with the Flanagan-Belytschko uniform gradient
// B_a = (1/V) int dN_a/dX dV reproduces any linear displacement field exactly on any hex
// (patch test), and does not lock volumetrically. Its spurious zero-energy modes (hourglass)
// are resisted by forces on the FB hourglass vectors
//   gamma_alpha,a = (1/8) [h_alpha,a - (sum_b h_alpha,b X_b) . B_a],
// which are orthogonal to every linear field, so hourglass forces vanish for rigid motion and
// constant strain. The hourglass stiffness is "physical" (after Belytschko & Bindeman 1993):
// for a box element of sides L_k, the mode u_i = delta * (product of natural coordinates in
// S) stores the energy of the linear strain it represents, E for the normal strain along i
// (bending; the parasitic shear is what incompatible modes remove) and mu for the shear of a
// direction outside S (warping), averaged over the element:
//   k_alpha,i = V sum_{k in S} (4 / L_k^2) (1/3)^(|S|-1) (E if k == i, else mu if i not in S)
// With that stiffness a box element bends like an incompatible-mode element, so a beam with
// n elements through its thickness gets its bending right and keeps about 1/n^2 of the
// bending energy in the hourglass modes. Distorted elements use the orthonormalized frame of
// their centre Jacobian. The stiffness is applied to the hourglass displacements in the
// reference frame (rejected: a co-rotational hourglass frame, which would cost a polar
// decomposition per element; rigid rotation still gives zero force because q = 0 then).
//
// Kinematics are total Lagrangian: F = sum_a x_a B_a^T, Green-Lagrange E = (F^T F - I)/2,
// second Piola-Kirchhoff stress S from the material, nodal forces f_a = V0 F S B_a. Rigid
// rotations give E = 0 exactly; small strains reduce to linear elasticity.
#pragma once

#include <Eigen/Core>
#include <array>

namespace kneesim::engine::solid {

inline constexpr int kHexNodes = 8;
inline constexpr int kHourglassModes = 4;

// natural coordinates of the nodes: the usual ordering, bottom face (zeta = -1) counter-
// clockwise seen from +zeta, then the top face
inline constexpr std::array<std::array<double, 3>, kHexNodes> kHexNatural = {{
    {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
    {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}}};

using HexPoints = std::array<Eigen::Vector3d, kHexNodes>;  // node positions [m]

// reference geometry of one element, precomputed once
struct Hex8Reference {
  double volume = 0.0;                                  // V0 [m^3]
  Eigen::Matrix<double, kHexNodes, 3> gradient;         // B_a = (1/V) int dN_a/dX dV [1/m]
  Eigen::Matrix<double, kHourglassModes, kHexNodes> gamma;  // FB hourglass vectors [-]
  // hourglass stiffness per mode, symmetric 3x3 in the reference frame [N/m]
  std::array<Eigen::Matrix3d, kHourglassModes> hourglass_stiffness;
  // sum_a gamma_alpha,a X_a, zero up to rounding; subtracted so that q measures displacement
  std::array<Eigen::Vector3d, kHourglassModes> hourglass_offset;
  double characteristic_length = 0.0;  // V0 / largest face area [m]
  double min_jacobian = 0.0;           // smallest det J at the 8 corners [m^3 / 8]
};

// gradient, volume, hourglass vectors and the shape part of the hourglass stiffness for the
// given reference node positions, with Young's modulus E and shear modulus mu [Pa]
Hex8Reference make_hex8_reference(const HexPoints& X, double youngs_modulus, double shear_modulus);

// det J at each corner of the element (negative or zero: inverted or degenerate) [m^3 / 8]
std::array<double, kHexNodes> calc_corner_jacobians(const HexPoints& x);

// the largest face area of the element [m^2]
double calc_max_face_area(const HexPoints& x);

// deformation gradient F = sum_a x_a B_a^T at the element centre
inline Eigen::Matrix3d calc_deformation_gradient(const Eigen::Matrix<double, kHexNodes, 3>& B,
                                                 const HexPoints& x) {
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
  for (int a = 0; a < kHexNodes; ++a) F += x[a] * B.row(a);
  return F;
}

}  // namespace kneesim::engine::solid
