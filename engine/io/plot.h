// Plots are Python scripts in tools/plots/, run with Debian's /usr/bin/python3 and matplotlib
// (MPLBACKEND=Agg). A missing interpreter or a failing script is a warning, not a failed run:
// the CSV and JSON results are complete without the PNG.
//
// A command that plots after a long simulation opens a PlotSession first: one interpreter
// (tools/plots/plot_server.py) starts at once and imports matplotlib on the other core while
// the simulation runs, then runs every plot of the command in the order asked, while the
// caller goes on. Importing matplotlib is about 0.8 s of CPU of a ~1.3 s plot; `kneesim
// compare` made four plots with four interpreters (CHANGELOG.md, performance round 3).
#pragma once

#include <string>
#include <vector>

namespace kneesim::io {

// runs tools/plots/<script> with the given arguments. Without a session: waits for it and
// returns true when the PNG was made, otherwise prints one warning line to stderr and returns
// false. Inside a session: queues it and returns true; the session's end waits for it and
// warns as above. Thread-safe.
bool run_plot(const std::string& script, const std::vector<std::string>& args);

// one plotting interpreter for the plots of a command, from construction (open it after the
// input is checked: it starts a process) to destruction (waits for the queued plots; ends the
// interpreter at once when none was queued). At most one at a time per process.
class PlotSession {
 public:
  PlotSession();
  ~PlotSession();
  PlotSession(const PlotSession&) = delete;
  PlotSession& operator=(const PlotSession&) = delete;
};

}  // namespace kneesim::io
