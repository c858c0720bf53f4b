#include "engine/io/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace kneesim::io {

ProgressBar::ProgressBar(std::string label, double delay_s)
    : label_(std::move(label)),
      delay_s_(delay_s),
      enabled_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(double fraction, const std::string& detail) {
  detail_ = detail;
  update(fraction);
}

void ProgressBar::update(double fraction) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < delay_s_) return;
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
