// Small text helpers shared by the diagnosis reports: a number through a printf format, and the
// wall time since a start point. One copy instead of one per case file.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace kneesim::diagnosis {

// `v` formatted with the printf format `f` (one double conversion, e.g. "%.3f")
inline std::string fmt(const char* f, double v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// wall seconds since `t0`
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace kneesim::diagnosis
