// Command-line options every `kneesim diagnose <case>` takes (output folder, bootstrap, seed,
// thresholds), validated into the library's DiagnosisOptions.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "analysis/diagnosis/diagnose.h"

namespace kneesim::cli {

struct DiagnoseCommonOptions {
  std::string out = "kneesim-diagnose";  // output folder
  int bootstrap = 200;               // bootstrap resamples [-]
  std::uint64_t seed = 1;            // bootstrap seed [-]
  double ic_threshold = 12.0;        // required AICc drop against none [-]
  double heldout_threshold = 0.05;   // required relative held-out RMSE drop [-]
  std::string noise_model = "instrument";  // error model: white, correlated, instrument
  std::vector<std::string> noise_params;   // key=value of the error model
  int detection_replicates = 20;     // replicates per detection limit, 0: none [-]
};

void add_diagnose_common_options(CLI::App* cmd, DiagnoseCommonOptions& o);

// the knee diagnoses' rigid contact law: with --no-calibrate, contact.calibration = "off" joins
// `sets`; the config's law is resolved and its fallback warning printed. A law missing under
// contact.calibration = "first_use" is calibrated by the diagnosis once its measured data are
// read (run::ensure_contact_law), and every config it loads from the same implant and material
// then finds it (InputError as load_config)
void prepare_contact_law(const std::string& config, std::vector<std::string>& sets,
                         bool no_calibrate);
// validated DiagnosisOptions (InputError naming the option)
diagnosis::DiagnosisOptions make_diagnosis_options(const DiagnoseCommonOptions& o);

}  // namespace kneesim::cli
