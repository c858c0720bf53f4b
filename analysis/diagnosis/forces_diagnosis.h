// The forces diagnosis as a library call (config + overrides -> Model -> forward simulations
// per measured cycle -> diagnosis -> files in `out`); `kneesim diagnose forces` is a thin shell.
// Besides the shared outputs (diagnosis_output.h) it reports the gain against the trivial
// predictor (the mean measured medial share of the training cycle times each row's measured
// total), the check of the grid surrogate against a direct simulation at the fitted value, the
// medial share per cycle, and the parameters that ended at a search bound (such a fit is not
// named: the result is `none`).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/diagnosis/diagnose.h"
#include "analysis/diagnosis/forces_case.h"

namespace kneesim::diagnosis {

struct ForcesDiagnosisOptions {
  std::string measured, config;   // CSV ("" = the config's gait.measured.file) and TOML
  std::vector<std::string> sets;  // key=value overrides
  ForcesCaseOptions case_options;
  int threads = 2;                // simulations run at a time [-]
  DiagnosisOptions options;
  std::string out = "kneesim-diagnose-forces";
};

struct ForcesDiagnosisReport {
  std::string summary_line;       // write_diagnosis's line (newline-terminated)
  DiagnosisResult result;
  nlohmann::json extra;           // the forces-specific keys added to diagnosis.json
  int simulations = 0;            // rig simulations [-]
  double sim_seconds = 0.0;       // [s]
  double total_seconds = 0.0;     // [s]
};

// throws InputError for bad input (naming the option, file, row and column)
ForcesDiagnosisReport run_forces_diagnosis(const ForcesDiagnosisOptions& o);

// the diagnosis of an assembled case with the forces rules (bound rule, trivial predictor,
// surrogate check); used by run_forces_diagnosis and the hidden-effect tests
ForcesDiagnosisReport diagnose_forces(const DiagnosisCase& c, ForcesSimulator& sim,
                                      const std::vector<double>& total_N,
                                      const DiagnosisOptions& options);

}  // namespace kneesim::diagnosis
