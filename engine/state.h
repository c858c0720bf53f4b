// State: the integration state only (design.md) — time, carriage poses and the DOF rates at
// the last half step, and a deformable insert's nodes and plastic state. Copyable, hashable,
// checkpointable; nothing derivable lives here.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "engine/model.h"

namespace kneesim::engine {

struct CarriageState {
  Eigen::Vector3d pivot_W = Eigen::Vector3d::Zero();   // pivot position [m], world
  Eigen::Matrix3d R_WB = Eigen::Matrix3d::Identity();  // carriage orientation
  std::array<double, kNumDof> rate{};  // DOF rates at t - dt/2 [m/s or rad/s], Dof order
};

struct State {
  double time = 0.0;                        // [s]
  long step = 0;                            // steps taken
  std::array<CarriageState, 2> carriages;   // indexed by Carriage
  solid::SolidState insert_solid;           // nodes and plastic state of a deformable insert
};

// FNV-1a hash over every bit of the state, for determinism tests and checkpoints
uint64_t hash_state(const State& state);

}  // namespace kneesim::engine
