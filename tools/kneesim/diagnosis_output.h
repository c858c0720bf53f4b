// Writing a diagnosis to its output folder, shared by every `kneesim diagnose <case>`:
// diagnosis.json, diagnosis.md, residuals.csv, curves.csv (all atomic) and diagnosis.png
// (tools/plots/diagnosis.py), plus one summary line on stdout.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>

#include "analysis/diagnosis/diagnose.h"
#include "analysis/diagnosis/diagnosis_case.h"

namespace kneesim::cli {

// options every diagnosis case takes
struct DiagnoseCommonOptions {
  std::string out = "out/diagnose";  // output folder
  int bootstrap = 200;               // bootstrap resamples [-]
  std::uint64_t seed = 1;            // bootstrap seed [-]
  double ic_threshold = 12.0;        // required AICc drop against none [-]
  double heldout_threshold = 0.05;   // required relative held-out RMSE drop [-]
};

void add_diagnose_common_options(CLI::App* cmd, DiagnoseCommonOptions& o);
// validated DiagnosisOptions (InputError naming the option)
diagnosis::DiagnosisOptions make_diagnosis_options(const DiagnoseCommonOptions& o);

void write_diagnosis(const diagnosis::DiagnosisCase& c, const diagnosis::DiagnosisResult& r,
                     const std::filesystem::path& out);

}  // namespace kneesim::cli
