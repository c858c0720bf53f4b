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
// The rig is driven by the measured total and flexion low-pass filtered at the cutoff of
// Winter's residual analysis (loads/iso14243/lowpass.h): the rig follows the gait, not the
// cells' noise; and not below 2 % of the record's peak total (a rig presses, it cannot pull:
// the cells' offsets and noise in swing would lift the femur off). The predicted medial force of a row is the rig's medial share at that phase
// times the row's MEASURED total: the measured total enters the prediction once, as it enters
// the trivial predictor (the mean share times the measured total), so the cells' noise common
// to the medial reading and the total cancels alike in both; driving the rig with the raw
// total instead fed that noise through the rig's dynamics into the share and the prediction
// (on clean synthetic sets with realistic noise the rig then lost to the trivial predictor,
// 27.6 against 20.7 N and 54.9 against 17.0 N RMS).
// The fits evaluate each candidate on a grid of full simulations across its parameter bounds
// and interpolate between grid points (cubic, per sample); the chosen fit is checked with a
// direct simulation at the fitted value (surrogate_rms_N in the report).
// Baseline: the rig as configured, no parameter refitted (the practitioner's rig offset).
// Error model (error_model.h, "instrument"): the residuals of the record are correlated in
// time (Ornstein-Uhlenbeck, one series over the whole record); nuisance terms of the load
// cells: an offset and a linear drift of the medial reading (free), and the cells' gain and
// crosstalk as they reach the residual medial - share x total. The medial reading and the
// total are read from the same cells, so, to first order in the errors, with s the predicted
// share and T the measured total: the gain of the medial cells minus that of the lateral ones
// times s (1 - s) T (a gain common to all cells cancels in the share), the crosstalk of the
// lateral cells into the medial reading times (1 - s)^2 T and that of the medial cells into
// the lateral reading (which enters the total) times -s^2 T; each gain and crosstalk fraction
// with a Gaussian prior of sd gain_crosstalk_sd (default 0.02: instrumented implants measure
// to 1-2 % of their calibration range including crosstalk, Bergmann et al., J Biomech Eng
// 130(2):021009, 2008; the gain difference sqrt(2) times that). A constant load-line shift moves
// the medial share by a nearly constant amount (0.0236 per mm on the built-in implant, 6-9 % of
// its signal outside the instrument's columns), which these terms also do: at noise of 20 N
// and more it is identified through the prior only, from about 2 mm (docs/diagnosis.md,
// forces case). The
// gain and crosstalk terms are not carried into held-out predictions
// (NuisanceTerm::carried_to_heldout): carried, `none` borrowed from the training cycle a
// calibration correction of any size, unbounded by the prior, and predicted a load-line shift
// on the held-out cycle as well as the effect did.
// Held-out rule: fit on one cycle, predict the other, both ways; with a single cycle in the
// file, interleaved 10 % gait-phase blocks (fit on the even blocks, predict the odd, and back).
// The quantity fitted is the medial force (the total is the rig's input; the lateral force is
// its complement); the report also gives the lateral force and the medial share.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "analysis/diagnosis/diagnosis_case.h"
#include "analysis/diagnosis/forces_sim.h"
#include "loads/iso14243/lowpass.h"
#include "models/config.h"

namespace kneesim::diagnosis {

struct ForcesMeasured {
  MeasuredData data;                  // medial_force_N rows, group = cycle name
  std::vector<ForcesCycle> cycles;    // the rig's loads per cycle
  std::vector<double> total_N;        // measured total axial force per row [N]
  std::vector<double> time_s;         // time of each row in the record [s] (gait % for a
                                      // table in percent)
  bool two_cycles = true;             // false: one cycle, phase-block held-out rule
  // the rig channels' low-pass filter: cutoff [Hz] and the noise RMS estimate of the residual
  // analysis, per channel (empty for a table in gait percent: not filtered)
  std::map<std::string, loads::CutoffChoice> input_filter;
  double axial_floor_N = 0.0;         // least axial force the rig is driven with [N]
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

// the forward model's prediction of every row of `measured` from a direct simulation of
// `effect` at `value` (no grid): the rig's medial share at the row's gait % times the row's
// measured total [N]; NaN in every row of a cycle whose simulation stopped
Eigen::VectorXd simulated_medial(ForcesSimulator& sim, const ForcesMeasured& measured,
                                 Effect effect, double value);

}  // namespace kneesim::diagnosis
