// Progress on stderr once the run has lasted longer than `delay_s` (short runs stay quiet):
// on a terminal a one-line bar redrawn at most ten times a second; otherwise (a log file, a
// pipe, a batch job) a line "label: 40 % done, 96 s elapsed, about 144 s left" each time the
// run passes another 10 % or every 30 s, whichever comes first, but at most one per 5 s.
#pragma once

#include <chrono>
#include <string>

namespace kneesim::io {

class ProgressBar {
 public:
  // min_gap_s: the least time between two log lines (tests shorten it)
  explicit ProgressBar(std::string label, double delay_s = 1.5, double min_gap_s = 5.0);
  ~ProgressBar();
  // fraction in [0, 1]
  void update(double fraction);
  // with a short text after the bar, e.g. "120/1000 trials, 2 failed"
  void update(double fraction, const std::string& detail);
  void finish();

 private:
  std::string label_;
  std::string detail_;
  double delay_s_;
  double min_gap_s_;
  bool enabled_;           // stderr is a terminal: the bar
  bool log_lines_;         // it is not: a line now and then
  int logged_tenths_ = 0;  // the last 10 % step a line reported
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_draw_, last_line_;

  void log_line(double fraction, double elapsed);
};

}  // namespace kneesim::io
