// Contact and scar geometry of the block-on-ring model (physics.md section 7, after Zhao 2008):
// a rigid ring of radius R_c pressed with load F into a Winkler block that has lost volume V
// as a circular scar of radius R_w. Unknowns theta (contact half-angle on the ring), theta'
// (half-angle of the scar arc) and R_w, from three equations solved with KINSOL:
//
//   R_c sin(theta) = R_w sin(theta')                          the scar spans the contact width
//   V = R_w^2 (theta' - sin theta' cos theta') w                circular-segment scar volume
//   F = C [R_c^2 (theta - sin theta cos theta) w - V]          foundation equilibrium
//
// Design: KINSOL iterates on (theta, theta', kappa = R_c / R_w) instead of R_w, because R_w
// tends to infinity as V -> 0 while kappa tends to 0 smoothly; theta - sin theta cos theta is
// evaluated by its series for small angles (it cancels to (2/3) theta^3). The unworn state
// (V = 0) is the one-equation limit, also solved with KINSOL. BorContactTable tabulates the
// geometry against V for one load so that the diagnosis can run thousands of forward
// evaluations without a nonlinear solve each (it interpolates a KINSOL-solved grid).
#pragma once

#include <vector>

#include "wear/bor/bor_rig.h"

namespace kneesim::bor {

struct BorContact {
  double volume = 0.0;          // V, worn volume [m^3]
  double theta = 0.0;           // contact half-angle on the ring [rad]
  double theta_scar = 0.0;      // theta', half-angle of the scar arc [rad]; 0 when unworn
  double scar_curvature = 0.0;  // kappa = R_c / R_w [-]; 0 when unworn
  double scar_depth = 0.0;      // R_w (1 - cos theta'), deepest point of the scar [m]
  double penetration = 0.0;     // ring penetration below the original surface [m]
  double contact_width = 0.0;   // 2 R_c sin(theta) [m]
  double contact_area = 0.0;    // 2 R_c w sin(theta) [m^2]
  double mean_pressure = 0.0;   // F / A [Pa]
  long iterations = 0;          // KINSOL iterations [-]
};

// theta - sin(theta) cos(theta), accurate for small theta [-]
double segment_factor(double theta);

// solves the three-equation model at load F [N] and worn volume V [m^3]; `guess` (optional)
// warm-starts KINSOL; throws std::runtime_error when KINSOL does not converge
BorContact solve_bor_contact(const BorRig& rig, double load, double volume,
                             const BorContact* guess = nullptr);

// geometry against worn volume for one load, on a grid solved with KINSOL. The grid is the
// fixed sequence V_i = V_base (i / (points - 1))^2 (finer near V = 0, where depth and width
// change fastest), extended by appending nodes when a larger volume is asked for, so that an
// interpolated value never depends on which volumes were requested before (determinism).
class BorContactTable {
 public:
  BorContactTable(const BorRig& rig, double load, double base_volume, int points = 241);
  // interpolated geometry at V [m^3]; extends the grid (KINSOL) when V exceeds it; throws
  // std::runtime_error beyond kMaxNodes nodes or when the contact cannot be solved
  BorContact at(double volume);
  // appends nodes until the grid reaches V [m^3]
  void extend_to(double volume);
  double load() const { return load_; }
  double max_volume() const { return volumes_.back(); }
  const std::vector<double>& volumes() const { return volumes_; }
  const std::vector<BorContact>& states() const { return states_; }

  static constexpr int kMaxNodes = 20000;

 private:
  void append_node();
  BorRig rig_;
  double load_;                     // F [N]
  double base_volume_;              // V_base [m^3]
  int points_;                      // nodes up to V_base [-]
  std::vector<double> volumes_;     // grid [m^3]
  std::vector<BorContact> states_;  // solved geometry at each grid volume
};

}  // namespace kneesim::bor
