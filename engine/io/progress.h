// A one-line progress bar on stderr, drawn only when stderr is a terminal and the run has
// lasted longer than `delay_s` (short runs stay quiet). Redraws at most ten times a second.
#pragma once

#include <chrono>
#include <string>

namespace kneesim::io {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label, double delay_s = 1.5);
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
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace kneesim::io
