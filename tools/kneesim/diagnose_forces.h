// `kneesim diagnose forces` (issue 16): measured medial compartment forces of an instrumented
// knee against the rig driven by the same measured loads. Registered by cmd_diagnose.cpp; the
// work is analysis/diagnosis/forces_diagnosis.h.
#pragma once

#include <CLI/CLI.hpp>

namespace kneesim::cli {

void add_diagnose_forces(CLI::App* diagnose);

}  // namespace kneesim::cli
