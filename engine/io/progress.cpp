#include "engine/io/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace kneesim::io {

ProgressBar::ProgressBar(std::string label, double delay_s, double min_gap_s)
    : label_(std::move(label)),
      delay_s_(delay_s),
      min_gap_s_(min_gap_s),
      enabled_(::isatty(STDERR_FILENO) != 0),
      log_lines_(!enabled_),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_),
      last_line_(start_) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(double fraction, const std::string& detail) {
  detail_ = detail;
  update(fraction);
}

void ProgressBar::log_line(double fraction, double elapsed) {
  constexpr double kMaxGap = 30.0;  // [s]
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_line_).count();
  const int tenths = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 10.0);
  if (since < min_gap_s_ || (tenths <= logged_tenths_ && since < kMaxGap)) return;
  last_line_ = now;
  logged_tenths_ = std::max(logged_tenths_, tenths);
  const double eta = fraction > 1e-6 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  std::fprintf(stderr, "%s: %.0f %% done, %.0f s elapsed, about %.0f s left%s%s\n",
               label_.c_str(), 100.0 * std::clamp(fraction, 0.0, 1.0), elapsed, eta,
               detail_.empty() ? "" : ", ", detail_.c_str());
  std::fflush(stderr);
}

void ProgressBar::update(double fraction) {
  if (!enabled_ && !log_lines_) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < delay_s_) return;
  if (log_lines_) {
    log_line(fraction, elapsed);
    return;
  }
  if (drawn_ && std::chrono::duration<double>(now - last_draw_).count() < 0.1) return;
  last_draw_ = now;
  drawn_ = true;
  fraction = std::clamp(fraction, 0.0, 1.0);
  constexpr int kWidth = 40;
  const int filled = static_cast<int>(fraction * kWidth);
  const double eta = fraction > 1e-6 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  std::fprintf(stderr, "\r%s [%.*s%*s] %5.1f%%  %.0fs left %s ", label_.c_str(), filled,
               "########################################", kWidth - filled, "",
               100.0 * fraction, eta, detail_.c_str());
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (enabled_ && drawn_) {
    std::fprintf(stderr, "\r%*s\r", static_cast<int>(label_.size() + detail_.size()) + 70, "");
    std::fflush(stderr);
    drawn_ = false;
  }
}

}  // namespace kneesim::io
