// Stable time step of the central-difference scheme and quasi-static positioning.
//
// The contact stiffness is not known before the run (it grows with the contact area), so it is
// measured: the femur is pressed statically onto the insert at the peak axial load at several
// flexion angles, and at each pose the tangent stiffness of every free DOF is summed over the
// elements in contact, K_i = sum_e A_e dp/dd (J_ei . n_e)^2. With the diagonal generalized
// masses, omega_max^2 = max_i K_i / m_i, and dt = safety * (2 / omega_max) (sqrt(1 + z^2) - z)
// for a damping ratio z (physics.md section 5). The safety factor covers contact areas larger
// than those sampled.
#pragma once

#include <vector>

#include "engine/data.h"
#include "engine/model.h"
#include "engine/state.h"

namespace kneesim::engine {

struct StableStepReport {
  double omega_max = 0.0;       // highest natural frequency found [rad/s]
  double stiffness_max = 0.0;   // tangent stiffness of the governing DOF [N/m or N m/rad]
  int governing_carriage = 0;   // 0 femur, 1 tibia
  int governing_dof = 1;        // Dof index
  double dt_critical = 0.0;     // 2 / omega_max with the damping correction [s]
  double dt = 0.0;              // safety * dt_critical [s]
  double damping_beta = 0.0;    // stiffness-proportional contact damping giving the ratio [s]
  double governing_flexion = 0.0;  // flexion probe where omega_max was found [rad]
};

// moves the femoral carriage's IS DOF (state.carriages[0].pivot_W.y) so that the axial contact
// force balances `load` [N]; returns the contact force reached [N]
double position_femur_statically(const Model& model, State& state, Data& data, double load);

// contact tangent stiffness per DOF [N/m or N m/rad] at the current state
std::array<std::array<double, kNumDof>, 2> calc_contact_stiffness(const Model& model,
                                                                  const State& state,
                                                                  Data& data);

// the stable step for the model's masses and contact, probing the given flexion angles [rad]
// at the given peak axial load [N]; `damping_ratio` is the contact damping ratio to realise
StableStepReport calc_stable_time_step(const Model& model, double peak_load,
                                       const std::vector<double>& flexion_probes,
                                       double damping_ratio, double safety);

}  // namespace kneesim::engine
