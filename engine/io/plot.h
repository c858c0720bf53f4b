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
// warns as above. A plot that cannot write its PNG because the disk is full (the script exits
// with kPlotDiskFull, tools/plots/plotio.py) warns so in one line, or, without a session and
// with `disk_full_is_error`, throws std::runtime_error instead (the command then ends as any
// full disk does: exit 1, partial names). Thread-safe.
bool run_plot(const std::string& script, const std::vector<std::string>& args,
              bool disk_full_is_error = false);

// waits for the plots queued so far in the open session (returns at once without one), warns
// for each that failed as run_plot does, or, with `disk_full_is_error`, throws
// std::runtime_error for one that found the disk full. A command calls it before the summary
// that marks its result complete, so that a full disk cannot end in a "complete" run without
// its plots. Thread-safe.
void wait_for_plots(bool disk_full_is_error);

// the exit code of a plot script that found the disk full (ENOSPC or EDQUOT)
inline constexpr int kPlotDiskFull = 3;

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
