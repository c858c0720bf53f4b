// The forces diagnosis case (issue 16, `kneesim diagnose forces`): measured medial
// compartment forces of an instrumented knee against the force-controlled rig driven by the
// same measured loads.
//
// Measured data: the table of the config's [gait.measured] section (or --measured FILE read
// with the same spec), which must define `medial_force_N` (gait.measured.compare) and
// `axial_force_N`; the lateral force is the total minus the medial. Every sample is a row at
// its gait percent. Cycle 1 is the config's window (heel strike to heel strike); cycle 2 is
// the rest of the file folded onto the same period: the samples after the window (the next
// cycle, 0 % from the window's end) and, where those stop, the samples before the window at
// the same phase (the end of the previous cycle). Each cycle is simulated with its own loads.
//
// Forward model: ForcesSimulator (forces_sim.h), one simulation per cycle and parameter value.
// The fits evaluate each candidate on a grid of full simulations across its parameter bounds
// and interpolate between grid points (cubic, per sample); the chosen fit is checked with a
// direct simulation at the fitted value (surrogate_rms_N in the report).
// Baseline: the rig as configured, no parameter refitted (the practitioner's rig offset).
// Held-out rule: fit on one cycle, predict the other, both ways; with a single cycle in the
// file, interleaved 10 % gait-phase blocks (fit on the even blocks, predict the odd, and back).
// The quantity fitted is the medial force (the total is the rig's input; the lateral force is
// its complement); the report also gives the lateral force and the medial share.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "analysis/diagnosis/diagnosis_case.h"
#include "analysis/diagnosis/forces_sim.h"
#include "models/config.h"

namespace kneesim::diagnosis {

struct ForcesMeasured {
  MeasuredData data;                  // medial_force_N rows, group = cycle name
  std::vector<ForcesCycle> cycles;    // the rig's loads per cycle
  std::vector<double> total_N;        // measured total axial force per row [N]
  bool two_cycles = true;             // false: one cycle, phase-block held-out rule
};

// reads `file` (the config's gait.measured.file when empty) with the config's column spec;
// throws InputError naming file, row and column
ForcesMeasured read_forces_measured(const models::Config& config, const std::string& file);

struct ForcesCaseOptions {
  int grid_points = 9;   // full simulations per candidate and cycle across its bounds [-]
  // friction is not a default candidate: each candidate costs a grid of simulations, and on
  // the JW rig friction 0-0.2 moves the medial force by at most 26 N RMS (docs/diagnosis.md, forces case)
  std::vector<Effect> candidates = {Effect::load_line, Effect::vv_moment, Effect::vv_alignment};
};

DiagnosisCase make_forces_case(const ForcesMeasured& measured,
                               std::shared_ptr<ForcesSimulator> sim,
                               const ForcesCaseOptions& options = {});

}  // namespace kneesim::diagnosis
