// The kinematics diagnosis case (issue 4, `kneesim diagnose kinematics`). Measured data: CSV
// with columns gait_pct, ap_mm, ie_deg (others ignored), or the Grand Challenge DM .sto file
// read by loads::read_kinematics about the engine's femoral reference point.
//
// Forward model: the force-controlled rig simulation of the config (kinematics_sim.h).
// Baseline: the configured rig as practitioners run it, compared after registering the
// measured reference frame: AP and IE offsets (measured minus model, averaged over the
// training rows) absorb the zero of the measurement (fluoroscopic registration, the rig's zero
// position); they are refitted with every candidate. Effects: friction (mu) and restraint
// (stiffness scale and AP laxity gap of the soft-tissue restraint).
// Held-out rule: 2-fold cross-validation by gait phase: fit on stance (0-60 %), predict swing;
// fit on swing, predict stance. A parameter that fits one phase only (a curve fit) does not
// carry over to the other phase; a physical cause does.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "analysis/diagnosis/diagnosis_case.h"
#include "analysis/diagnosis/kinematics_sim.h"

namespace kneesim::diagnosis {

struct KinematicsCaseOptions {
  double stance_end_pct = 60.0;  // stance / swing boundary of the phase split [%]
};

// reads the measured kinematics: a CSV (gait_pct, ap_mm, ie_deg) or a .sto file; p_FR_F is
// the femoral reference point for .sto files [m] (config.femur_origin_mm for mesh implants)
MeasuredData read_kinematics_measured(const std::string& path, const Eigen::Vector3d& p_FR_F);

// the femoral reference point of a config, as `kneesim run` uses it for its overlay [m]
Eigen::Vector3d femoral_reference_point(const models::Config& config);

DiagnosisCase make_kinematics_case(MeasuredData data, std::shared_ptr<KinematicsSimulator> sim,
                                   const KinematicsCaseOptions& options);

}  // namespace kneesim::diagnosis
