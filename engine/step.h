// One explicit step of the rig: a short list of stages (design.md "one readable step").
#pragma once

#include "engine/data.h"
#include "engine/model.h"
#include "engine/state.h"

namespace kneesim::engine {

enum class StepStatus {
  kOk,
  kNotFinite,
  kRunawayPenetration,
  kRunawayMotion,
  kUnstableStep,  // the contact stiffened beyond what the time step can integrate
  kInvertedElement,  // an element of the deformable insert inverted (det F <= 0)
};

// omega_max * dt over the central-difference limit 2 (sqrt(1 + z^2) - z) with the current
// contact damping ratio z; above 1 the scheme is unstable
double calc_stability_ratio(const Model& model, const Data& data);

const char* to_string(StepStatus status);

// kRunawayMotion when a carriage moved more than 50 mm or turned more than 60 deg from its
// start, kRunawayPenetration when the deepest overlap passes contact.runaway_fraction of the
// insert's thickness or leaves the distance field's band, else kOk (data: after calc_forces);
// every integrator stops on them
StepStatus find_runaway(const Model& model, const Data& data);

// advances state by model.dt with the central-difference scheme; never allocates, never throws
StepStatus step(const Model& model, State& state, Data& data);

// evaluates kinematics, contact and loads at the current state without advancing it (used by
// the first frame, the reference integrator and quasi-static positioning)
void calc_forces(const Model& model, const State& state, Data& data);

// the state at t = 0: every DOF at its initial or prescribed value, rates zero
State make_initial_state(const Model& model);

}  // namespace kneesim::engine
