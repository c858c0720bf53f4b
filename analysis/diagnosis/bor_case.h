// The block-on-ring diagnosis case (issue 4, `kneesim diagnose bor`). Measured data: CSV with
// columns load_N, cycles, volume_mm3 and optional depth_mm (penetration after unloading) and
// specimen. Forward model: the semi-analytic model of wear/bor with one wear law per effect.
// Calibration rule (Hussin 2024): k_D from the least-squares slope of volume against cycles
// over the steady-state points (cycles >= steady_state_from) at the calibration load.
// Held-out split: leave-one-specimen-out when every load has two or more specimens, otherwise
// leave-one-load-out. Candidates: running_in and pressure_dependent_wear always (two loads are
// required), creep when depth was measured (creep changes depth, not volume).
#pragma once

#include <string>

#include "analysis/diagnosis/diagnosis_case.h"
#include "wear/bor/bor_rig.h"

namespace kneesim::diagnosis {

struct BorCaseOptions {
  bor::BorRig rig;                           // Hussin 2024 rig by default
  double calibration_load = 225.0;           // load of the practitioner's calibration [N]
  double steady_state_from = 50000.0;        // first cycle count of the steady state [cycles]
};

// reads and validates the measured CSV (InputError names file, row and column)
MeasuredData read_bor_measured(const std::string& path);

// the case; throws InputError when the data hold a single load
DiagnosisCase make_bor_case(MeasuredData data, const BorCaseOptions& options);

// "225 N" label of a load [N]
std::string bor_load_label(double load);

}  // namespace kneesim::diagnosis
