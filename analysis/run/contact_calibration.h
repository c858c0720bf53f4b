// Calibrating the rigid path's elastic-foundation law against the deformable insert (issue 11
// item 6, after Halloran 2005): the pressure traces of two runs over the gait cycle, their
// error, and the one-dimensional search over the effective foundation modulus
// (models/contact_law_file.h says why one modulus). `kneesim calibrate-contact` is the shell.
//
// Error measure: over the frames of a window of the cycle where both runs are in contact, the
// normalized RMS sqrt(sum (r - d)^2 / sum d^2) of the rigid trace r against the deformable one
// d, for the frame's peak pressure, its mean contact pressure and its contact area. The fit
// minimizes peak^2 + mean^2 on the fitting window; the result is judged on a window it was not
// fitted on too.
#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

namespace kneesim::run {

struct PressureTrace {
  std::vector<double> gait_pct;       // [%]
  std::vector<double> peak_MPa;       // frame peak pressure [MPa]
  std::vector<double> mean_MPa;       // frame mean contact pressure [MPa]
  std::vector<double> area_mm2;       // contact area [mm^2]
};

// the columns gait_pct, peak_pressure_MPa, mean_pressure_MPa, contact_area_mm2 of a run's
// kinematics.csv; InputError naming the file and what is missing
PressureTrace read_pressure_trace(const std::filesystem::path& kinematics_csv);

struct TraceErrors {
  double peak = 0.0;   // normalized RMS error of the frame peak pressure [-]
  double mean = 0.0;   // of the mean contact pressure [-]
  double area = 0.0;   // of the contact area [-]
  int frames = 0;      // frames compared
};

// rigid against deformable over lo <= gait_pct <= hi; rows matched by index, each run's 1 %
// frames (std::invalid_argument when the row counts differ or a pair is more than half a
// percent apart)
TraceErrors compare_traces(const PressureTrace& rigid, const PressureTrace& deformable,
                           double lo_pct, double hi_pct);

// a run's pressure figures over a window of the cycle (the frames in contact): the largest
// frame peak, the mean of the frame peak, the mean contact pressure and the mean contact area
struct WindowFigures {
  double peak_MPa = 0.0;
  double mean_peak_MPa = 0.0;
  double mean_MPa = 0.0;
  double area_mm2 = 0.0;
  int frames = 0;
};
WindowFigures calc_window_figures(const PressureTrace& trace, double lo_pct, double hi_pct);

// the two as summary.json reports them (peak_pressure_rms, ...; peak_MPa, mean_peak_MPa, ...)
nlohmann::json trace_errors_json(const TraceErrors& errors);
nlohmann::json window_figures_json(const WindowFigures& figures);

// the calibration's windows of the cycle [%]: fitted on 0-30, held out on 30-60, stance 0-60
inline constexpr double kFitWindowLo = 0.0, kFitWindowHi = 30.0;
inline constexpr double kHeldOutLo = 30.0, kHeldOutHi = 60.0;
inline constexpr double kStanceLo = kFitWindowLo, kStanceHi = kHeldOutHi;

// summary[w][rigid_key] = the errors of `rigid` against `deformable` over each window w:
// fit_window_0_30pct, held_out_30_60pct, stance_0_60pct
void add_window_errors(nlohmann::json& summary, const char* rigid_key, const PressureTrace& rigid,
                       const PressureTrace& deformable);

// out/comparison.csv: gait_pct and the deformable_, rigid_ (the law as specified) and
// calibrated_ peak_MPa, mean_MPa and area_mm2 columns, the three traces' rows matched by index
void write_pressure_comparison(const std::filesystem::path& csv, const PressureTrace& deformable,
                               const PressureTrace& specified, const PressureTrace& calibrated);

// golden-section search for the minimum of f(x) over log x in [lo, hi] until the bracket is
// within `rel_tol` (relative); `evaluations` counts the calls of f. A minimum at a bound is
// returned as that bound (the caller reports it: a fit at a bound is not a finding)
double minimize_log_golden(const std::function<double(double)>& f, double lo, double hi,
                           double rel_tol, int& evaluations);

}  // namespace kneesim::run
