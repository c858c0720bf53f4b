// The reports of the commands without a 3D view, one call each from the command after its
// outputs are written (analysis/report/summary_report.h says what such a report holds).
#pragma once

#include <filesystem>
#include <string>

namespace kneesim::report {

void write_bor_report(const std::filesystem::path& out);
void write_particles_report(const std::filesystem::path& out);
void write_calibrate_report(const std::filesystem::path& out, const std::string& material);
// check-contact: the same traces, the calibrated column being the law the commands use
void write_check_contact_report(const std::filesystem::path& out, const std::string& material);
void write_study_report(const std::filesystem::path& out, const std::string& method);
// every `kneesim diagnose` kind: diagnosis.json and diagnosis.md
void write_diagnosis_report(const std::filesystem::path& out, const std::string& kind);

}  // namespace kneesim::report
