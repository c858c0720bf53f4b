// Reference integrator: the same rigid-body rig equations, m_i qdd_i = Q_i(q, qd, t) - c_i qd_i
// over the free and force-driven DOFs, integrated by SUNDIALS CVODE (BDF, adaptive order and
// step) instead of the central-difference scheme. Locked and prescribed DOFs enter as known
// functions of time. Used to cross-check the explicit integrator (kinematic agreement and a
// CPU-time ratio in the benchmark); selected with solver.integrator = "cvode".
#pragma once

#include "engine/simulate.h"

namespace kneesim::engine {

RunResult simulate_reference(const Model& model, State& state, Data& data,
                             const RunOptions& options);

}  // namespace kneesim::engine
