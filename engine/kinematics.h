// Kinematics stage: DOF values, gimbal axes and part poses from the State.
#pragma once

#include "engine/data.h"
#include "engine/model.h"
#include "engine/state.h"

namespace kneesim::engine {

// fills data.q, data.angles, data.axes, data.X_WF, data.X_WT
void update_kinematics(const Model& model, const State& state, Data& data);

// world velocity [m/s] of the material point at p_W moving with carriage c (half-step rates)
Eigen::Vector3d find_point_velocity(const State& state, const Data& data, int c,
                                    const Eigen::Vector3d& p_W);

// pose of a carriage's implant part in the world for given DOF values
Eigen::Isometry3d calc_part_pose(const CarriageModel& carriage,
                                 const std::array<double, kNumDof>& q);

}  // namespace kneesim::engine
