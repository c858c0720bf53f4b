// The knee cases of `kneesim diagnose` (issue 4): knee-wear (volume and depth per condition of
// a knee simulator test) and kinematics (measured AP and IE against the force-controlled rig).
// Registered by cmd_diagnose.cpp; the work is analysis/diagnosis/knee_diagnosis.h.
#pragma once

#include <CLI/CLI.hpp>

namespace kneesim::cli {

void add_diagnose_knee_wear(CLI::App* diagnose);
void add_diagnose_kinematics(CLI::App* diagnose);

}  // namespace kneesim::cli
