// One explicit step of the rig: a short list of stages (design.md "one readable step").
#pragma once

#include "engine/data.h"
#include "engine/model.h"
#include "engine/state.h"

namespace kneesim::engine {

enum class StepStatus { kOk, kNotFinite, kRunawayPenetration, kRunawayMotion };

const char* to_string(StepStatus status);

// advances state by model.dt with the central-difference scheme; never allocates, never throws
StepStatus step(const Model& model, State& state, Data& data);

// evaluates kinematics, contact and loads at the current state without advancing it (used by
// the first frame, the reference integrator and quasi-static positioning)
void calc_forces(const Model& model, const State& state, Data& data);

// the state at t = 0: every DOF at its initial or prescribed value, rates zero
State make_initial_state(const Model& model);

}  // namespace kneesim::engine
