// The rig's coupled implicit step (solver.rig_coupling = "coupled").
//
// Why: the default (partitioned) step integrates the light AP and IE DOFs implicitly, each in
// its own contact stiffness K_ii, while the femoral carriage's axial and VV DOFs move
// explicitly. With the axial DOF held for the step, a light DOF's Newton step toward
// equilibrium is short: on a conforming dish an AP move must lift the femur, which only the
// next steps do, so the two approach their common equilibrium like a block-Jacobi iteration
// whose contraction K_xy^2 / (K_xx K_yy) nears 1. The motion lags by a time proportional to
// the step; on the measured JW loads (low axial load, high AP force, condylar lift-off) the
// AP and IE ranges came out 16 % and 34 % below the CVODE reference at the default step
// (docs/validation.md, "Rig step"). The light DOFs' own stiffness is also off: the
// symmetric estimate sum k (n.J)^2 leaves out that the penetration grows along the femoral
// surface's normal, not the insert's (tibial AP at heel strike: 28 000 against 49 000 N/m).
//
// What: the light DOFs are solved together with the rest of the rig. Their rows are linearly
// implicit in the contact's tangent stiffness to every moved DOF, K_ij = sum_e k_e (n_e . J_i)
// (m_e . J_j) (n_e the insert's normal along which the force acts, m_e minus the femur's
// outward normal along which the penetration grows, J the point's velocity per unit DOF rate,
// + femur, - tibia; not symmetric where the surfaces do not conform), and in the restraint:
// the elastic force at x(n+1) = x(n) + dt u, the contact damper beta K at the new rate u.
// Their friction stays the capped implicit law of engine/implicit_friction.h, its secant line
// also moved by the other DOFs' rates through the same slip (C_ij = sum_e c_e J_i,t . J_j,t).
// The heavy DOFs (the femur's axial and VV, ML) keep their central-difference rows, so the
// light rows see their new rates within the step:
//   light:  (M/dt + D + (beta + dt) K) (u - v) = G - F - D v - dt K v + F(u)  (all columns)
//   heavy:  M/dt (u - v) = G - F - D v + F(u)                                (own column)
// solved by Gauss-Seidel sweeps in DOF order (fixed order: the same bits for any thread
// count; a few sweeps), each row in closed form with its friction cap. Making the heavy rows
// implicit too (tried) made every DOF first order in the step and put the materials_study
// rig's AP range 5 % low at the default step with the JW AP range still 8 % low.
#pragma once

#include <array>

#include <Eigen/Core>

namespace kneesim::engine {

struct Model;
struct Data;
struct State;

// DOF slot of carriage c, DOF i in the 12x12 coupling matrix
constexpr int coupling_slot(int c, int i) { return 6 * c + i; }

// the moved (free or force-driven) DOFs of both carriages, in slot order
struct CoupledDofs {
  std::array<int, 12> slot{};
  int n = 0;
};
CoupledDofs find_coupled_dofs(const Model& model);

// adds one contact element's (or node's) tangent stiffness ke [N/m] at point c_W to K
// (row-major 12x12 over slots): K_ij += ke (n_W . J_i) (m_W . J_j), the force along the
// insert's normal n_W, the penetration growing along m_W (minus the femoral surface's
// outward normal; n_W where the two surfaces conform; the two differ where they do not, and
// then K is not symmetric); J: the point's velocity per unit DOF rate, + femur, - tibia.
// axes: each carriage's gimbal axes, pivots: each carriage's pivot [m]
// With C and a friction slope ce [N s/m] (the regularized friction's secant,
// engine/contact.cpp) it also adds ce (J_i,t . J_j,t) to *C, J_t the tangential part (normal
// n_W removed): how one DOF's rate changes the friction on another (the same slip).
void add_contact_coupling(const CoupledDofs& dofs, double ke, double ce,
                          const Eigen::Vector3d& c_W, const Eigen::Vector3d& n_W,
                          const Eigen::Vector3d& m_W,
                          const std::array<std::array<Eigen::Vector3d, 3>, 2>& axes,
                          const std::array<Eigen::Vector3d, 2>& pivots,
                          std::array<double, 144>& K, std::array<double, 144>* C);

// one row of the coupled system per moved DOF: a (u - v) + sum_l off[l] (u_l - v_l) =
// b + F(u), F capped (implicit_friction.h)
struct CoupledSystem {
  int n = 0;
  std::array<double, 12> a{}, b{}, friction{}, secant{}, capacity{};
  std::array<double, 144> off{};  // row-major n x n, diagonal unused
  // the friction's secant slopes between rows: row k's friction is
  // clamp(friction_k - secant_k x_k - sum_l off_friction_kl x_l, -capacity_k, capacity_k)
  std::array<double, 144> off_friction{};
};

// the increments x = u - v solving the system by Gauss-Seidel sweeps until the largest
// change of a row's force a |dx| is below tol times the row's scale; returns the sweeps used
// (max_sweeps when not converged)
int solve_coupled_system(const CoupledSystem& sys, std::array<double, 12>& x,
                         double tol = 1e-12, int max_sweeps = 500);

// the new rates of every moved DOF into state: the light ones coupled, the heavy ones by
// central difference (the positions are advanced by the caller)
void update_coupled_rates(const Model& model, State& state, const Data& data);

}  // namespace kneesim::engine
