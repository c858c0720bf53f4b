// The knee cases of the diagnosis as library calls (config + overrides -> Models -> forward
// simulations -> diagnosis -> files in `out`): knee-wear (volume and depth per condition of a
// knee simulator test) and kinematics (measured AP and IE against the force-controlled rig).
// `kneesim diagnose knee-wear|kinematics` is a thin shell over these two functions.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/diagnosis/diagnose.h"

namespace kneesim::diagnosis {

struct KneeWearDiagnosisOptions {
  std::string measured, config;           // CSV and TOML paths
  std::vector<std::string> sets;          // key=value overrides of every condition
  std::string calibration_condition;      // "" = the first condition in the CSV
  double steady_state_from_cycles = 5e5;  // [cycles]
  int check_updates = 4;                  // wear-loop updates of the check, 0 = none [-]
  int geometry_states = 4;                // worn states of the forward model's geometry
                                          // path, 0 = pristine-linear (knee_wear_table.h) [-]
  DiagnosisOptions options;
  std::string out = "kneesim-diagnose-knee-wear";
};

struct KneeWearDiagnosisReport {
  std::string summary_line;    // write_diagnosis's line (newline-terminated)
  size_t conditions = 0;       // simulated conditions [-]
  double sim_seconds = 0.0;    // forward simulations [s]
  double total_seconds = 0.0;  // [s]
  nlohmann::json check;        // approximation_check.json (null when not run)
};

// throws InputError for bad input (naming the option or file)
KneeWearDiagnosisReport run_knee_wear_diagnosis(const KneeWearDiagnosisOptions& o);

struct KinematicsDiagnosisOptions {
  std::string measured, config;  // CSV or .sto, and TOML paths
  std::vector<std::string> sets; // key=value overrides
  double stance_end_pct = 60.0;  // end of stance in the phase split [%]
  int threads = 2;               // rig simulations run at a time [-]
  DiagnosisOptions options;      // multi_start included
  std::string out = "kneesim-diagnose-kinematics";
};

struct KinematicsDiagnosisReport {
  std::string summary_line;    // write_diagnosis's line (newline-terminated)
  int simulations = 0;         // rig simulations not served by the cache [-]
  double sim_seconds = 0.0;    // [s]
  double total_seconds = 0.0;  // [s]
};

KinematicsDiagnosisReport run_kinematics_diagnosis(const KinematicsDiagnosisOptions& o);

}  // namespace kneesim::diagnosis
