// The gait waveform a config drives the rig with, assembled from its parts:
//   1. the gait file (ISO 14243-shaped by default) with the sign conventions applied;
//   2. measured kinematics (displacement mode), merged in;
//   3. a measured load table over one gait cycle ([gait.measured], loads/iso14243/
//      measured_loads.h): its channels replace the gait file's (measured axial force and
//      flexion; the AP force and IE torque stay the rig's);
//   4. a varus-valgus torque on the tibial carriage, `vv_torque_Nm` (+ varus: loads the medial
//      condyle), = (arm + stance_arm x stance shape) x axial force, for the forces diagnosis:
//        arm: the axial load line moved medially by `arm` (a moment that follows the axial
//             force; gait.vv_torque_axial_arm_mm);
//        stance arm: a load-line shift that follows the gait phase: zero at heel strike and in
//             swing, two peaks in stance like the external knee adduction moment of walking
//             (an assumed shape, key points in gait_assembly.cpp; gait.vv_torque_stance_arm_mm).
//        Both are levers times the axial force: a free tibial VV has no restraint, so a torque
//        beyond axial force x half the condyle spacing would lift a condyle off (in the
//        patient the collateral ligaments carry that part).
// The diagnosis (analysis/diagnosis/forces_sim.h) calls the same functions on a built Model,
// so an effect it fits is exactly what `kneesim run --set gait.vv_torque_...` simulates.
#pragma once

#include "loads/iso14243/measured_loads.h"
#include "loads/iso14243/waveform.h"
#include "models/config.h"

namespace kneesim::models {

// the measured-load spec of a config's [gait.measured] section (file resolved)
loads::MeasuredLoadSpec measured_load_spec(const Config& config);

// rig channels a measured load table may drive
const std::vector<std::string>& measured_rig_channels();

// parts 1-3; `measured_cycle` replaces the config's measured-load cycle when given (another
// cycle of the same table)
loads::Waveform make_gait(const Config& config, const loads::Waveform* measured_cycle = nullptr);

// the stance-phase shape of the VV torque at gait percent (0..1, peak 1) [-]
double stance_vv_shape(double gait_pct);

// the gait with a `vv_torque_Nm` channel = (arm_mm + stance_arm_mm x stance_vv_shape) 1e-3
// x axial_force_N x axial_force_scale, added to an existing vv_torque_Nm channel (other channel
// indices unchanged); the gait unchanged when both are zero
loads::Waveform with_vv_torque(const loads::Waveform& gait, double arm_mm, double stance_arm_mm,
                               double axial_force_scale);

}  // namespace kneesim::models
