// Writing a diagnosis to its output folder, shared by every diagnosis case (block-on-ring,
// knee wear, kinematics): diagnosis.json, diagnosis.md, residuals.csv, curves.csv (all atomic)
// and diagnosis.png (tools/plots/diagnosis.py).
#pragma once

#include <filesystem>
#include <string>

#include "analysis/diagnosis/diagnose.h"
#include "analysis/diagnosis/diagnosis_case.h"

namespace kneesim::diagnosis {

// writes the files; returns the one-line summary for the caller to print (newline-terminated)
std::string write_diagnosis(const DiagnosisCase& c, const DiagnosisResult& r,
                            const std::filesystem::path& out);

// appends a section to the diagnosis.md written by write_diagnosis (atomically again)
void append_report(const std::filesystem::path& out, const std::string& section);

}  // namespace kneesim::diagnosis
