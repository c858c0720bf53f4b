// Plots are Python scripts in tools/plots/, run with Debian's /usr/bin/python3 and matplotlib
// (MPLBACKEND=Agg). A missing interpreter or a failing script is a warning, not a failed run:
// the CSV and JSON results are complete without the PNG.
#pragma once

#include <string>
#include <vector>

namespace kneesim::io {

// runs tools/plots/<script> with the given arguments; returns true when the PNG was made,
// otherwise prints one warning line to stderr and returns false
bool run_plot(const std::string& script, const std::vector<std::string>& args);

}  // namespace kneesim::io
