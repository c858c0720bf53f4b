#include "analysis/run/contact_calibration.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>

#include "engine/errors.h"
#include "engine/io/table.h"

namespace kneesim::run {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, ',')) cells.push_back(cell);
  return cells;
}

}  // namespace

PressureTrace read_pressure_trace(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line)) {
    throw InputError(file.string() + ": cannot read the run's kinematics table.");
  }
  const auto header = split(line);
  const char* names[4] = {"gait_pct", "peak_pressure_MPa", "mean_pressure_MPa",
                          "contact_area_mm2"};
  int col[4];
  for (int c = 0; c < 4; ++c) {
    col[c] = -1;
    for (size_t i = 0; i < header.size(); ++i) {
      if (header[i] == names[c]) col[c] = static_cast<int>(i);
    }
    if (col[c] < 0) {
      throw InputError(file.string() + ": row 1 lacks the column " + names[c] + ".");
    }
  }
  PressureTrace t;
  std::vector<double>* out[4] = {&t.gait_pct, &t.peak_MPa, &t.mean_MPa, &t.area_mm2};
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    const auto cells = split(line);
    for (int c = 0; c < 4; ++c) {
      char* end = nullptr;
      const double v = col[c] < static_cast<int>(cells.size())
                           ? std::strtod(cells[col[c]].c_str(), &end) : NAN;
      if (!end || *end != '\0' || !std::isfinite(v)) {
        throw InputError(file.string() + ": row " + std::to_string(row) + ", column " +
                         names[c] + " is not a finite number.");
      }
      out[c]->push_back(v);
    }
  }
  return t;
}

TraceErrors compare_traces(const PressureTrace& r, const PressureTrace& d, double lo, double hi) {
  if (r.gait_pct.size() != d.gait_pct.size()) {
    throw std::invalid_argument("compare_traces: the two runs hold different frames");
  }
  double sp = 0, dp = 0, sm = 0, dm = 0, sa = 0, da = 0;
  TraceErrors e;
  for (size_t i = 0; i < r.gait_pct.size(); ++i) {
    // each run writes one row per 1 % of its cycle, at its own steps (the rigid and the
    // deformable steps differ): rows are matched by index, within half a percent
    if (std::abs(r.gait_pct[i] - d.gait_pct[i]) > 0.5) {
      throw std::invalid_argument("compare_traces: the two runs hold different frames");
    }
    if (r.gait_pct[i] < lo || r.gait_pct[i] > hi) continue;
    if (!(r.area_mm2[i] > 0.0 && d.area_mm2[i] > 0.0)) continue;
    sp += std::pow(r.peak_MPa[i] - d.peak_MPa[i], 2);
    dp += d.peak_MPa[i] * d.peak_MPa[i];
    sm += std::pow(r.mean_MPa[i] - d.mean_MPa[i], 2);
    dm += d.mean_MPa[i] * d.mean_MPa[i];
    sa += std::pow(r.area_mm2[i] - d.area_mm2[i], 2);
    da += d.area_mm2[i] * d.area_mm2[i];
    ++e.frames;
  }
  if (e.frames == 0) return e;
  e.peak = std::sqrt(sp / dp);
  e.mean = std::sqrt(sm / dm);
  e.area = std::sqrt(sa / da);
  return e;
}

WindowFigures calc_window_figures(const PressureTrace& t, double lo, double hi) {
  WindowFigures f;
  for (size_t i = 0; i < t.gait_pct.size(); ++i) {
    if (t.gait_pct[i] < lo || t.gait_pct[i] > hi || !(t.area_mm2[i] > 0.0)) continue;
    f.peak_MPa = std::max(f.peak_MPa, t.peak_MPa[i]);
    f.mean_peak_MPa += t.peak_MPa[i];
    f.mean_MPa += t.mean_MPa[i];
    f.area_mm2 += t.area_mm2[i];
    ++f.frames;
  }
  if (f.frames > 0) {
    f.mean_peak_MPa /= f.frames;
    f.mean_MPa /= f.frames;
    f.area_mm2 /= f.frames;
  }
  return f;
}

nlohmann::json trace_errors_json(const TraceErrors& e) {
  return {{"peak_pressure_rms", e.peak}, {"mean_pressure_rms", e.mean},
          {"contact_area_rms", e.area}, {"frames", e.frames}};
}

nlohmann::json window_figures_json(const WindowFigures& f) {
  return {{"peak_MPa", f.peak_MPa}, {"mean_peak_MPa", f.mean_peak_MPa}, {"mean_MPa", f.mean_MPa},
          {"area_mm2", f.area_mm2}, {"frames", f.frames}};
}

void add_window_errors(nlohmann::json& summary, const char* rigid_key, const PressureTrace& rigid,
                       const PressureTrace& deformable) {
  for (const auto& [name, lo, hi] : {std::tuple{"fit_window_0_30pct", kFitWindowLo, kFitWindowHi},
                                     std::tuple{"held_out_30_60pct", kHeldOutLo, kHeldOutHi},
                                     std::tuple{"stance_0_60pct", kStanceLo, kStanceHi}}) {
    summary[name][rigid_key] = trace_errors_json(compare_traces(rigid, deformable, lo, hi));
  }
}

void write_pressure_comparison(const std::filesystem::path& csv, const PressureTrace& deformable,
                               const PressureTrace& specified, const PressureTrace& calibrated) {
  if (specified.gait_pct.size() != deformable.gait_pct.size() ||
      calibrated.gait_pct.size() != deformable.gait_pct.size()) {
    throw std::invalid_argument("write_pressure_comparison: the traces hold different frames");
  }
  io::Table t;
  t.columns = {"gait_pct", "deformable_peak_MPa", "deformable_mean_MPa", "deformable_area_mm2",
               "rigid_peak_MPa", "rigid_mean_MPa", "rigid_area_mm2", "calibrated_peak_MPa",
               "calibrated_mean_MPa", "calibrated_area_mm2"};
  for (size_t i = 0; i < deformable.gait_pct.size(); ++i) {
    t.add_row({deformable.gait_pct[i], deformable.peak_MPa[i], deformable.mean_MPa[i],
               deformable.area_mm2[i], specified.peak_MPa[i], specified.mean_MPa[i],
               specified.area_mm2[i], calibrated.peak_MPa[i], calibrated.mean_MPa[i],
               calibrated.area_mm2[i]});
  }
  io::write_csv(csv, t);
}

double minimize_log_golden(const std::function<double(double)>& f, double lo, double hi,
                           double rel_tol, int& evaluations) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = std::log(lo), b = std::log(hi);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(std::exp(c)), fd = f(std::exp(d));
  evaluations = 2;
  while (b - a > std::log1p(rel_tol)) {
    if (fc < fd) {
      b = d; d = c; fd = fc;
      c = b - g * (b - a);
      fc = f(std::exp(c));
    } else {
      a = c; c = d; fc = fd;
      d = a + g * (b - a);
      fd = f(std::exp(d));
    }
    ++evaluations;
  }
  return std::exp(fc < fd ? c : d);
}

}  // namespace kneesim::run
