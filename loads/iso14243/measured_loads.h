// Measured load tables (issue 16): a CSV of measured signals over time or gait percent (an
// instrumented implant's load cells, a goniometer, a force plate) turned into waveform channels
// the rig can be driven with, one gait cycle long and periodic.
//
// A channel is a weighted sum of columns, written `target = 0.9871 AM + 0.9683 PM + ...`, so a
// load-cell reduction (four cells -> total force, or -> the medial compartment) is data, not
// code. The target's unit suffix (_N, _Nm, _deg, _mm) says what kind of quantity it is; each
// column's unit comes from its header (`PM(lbf)`, `PM[lbf]`, `axial_force_N`) or, for a bare
// header, from the spec's unit for that kind (`force_unit = "lbf"`); a force column with
// neither is refused rather than assumed to be in newtons.
//
// Time: a column in s (or ms) with a window [start, end] that is one gait cycle (start = heel
// strike = 0 %), or a gait-percent column (window 0..100 by default). The cycle is resampled
// every 0.25 % by linear interpolation and made periodic by removing the linear drift between
// its ends (as for measured kinematics, models/build_model.cpp): a prescribed DOF must not jump
// at the cycle boundary, and the drift of a force over one cycle is a measurement artefact.
// Rejected: choosing heel strikes automatically (no channel marks them reliably in every
// file; the window is the user's documented choice).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "loads/iso14243/waveform.h"

namespace kneesim::loads {

struct MeasuredLoadSpec {
  std::filesystem::path file;           // the measured table (CSV)
  std::string origin;                   // where the spec comes from (config file), for messages
  std::string time_column;              // "" = the first column
  std::string time_unit;                // "" = from the header; "s", "ms" or "pct"
  std::vector<double> window;           // {start, end} in the time column's unit, or empty
  std::map<std::string, std::string> units;  // kind ("force", "moment", "angle", "length")
                                             // -> unit of bare column headers
  std::vector<std::string> channels;    // "target = expression" (weighted column sums)
};

struct MeasuredLoads {
  std::string source;                       // file name, for messages and waveform sources
  std::string time_name;                    // time column header as written
  bool percent = false;                     // time column is gait percent
  double window_start = 0.0, window_end = 0.0;  // one cycle [s or %]
  std::vector<double> time;                 // [s or %], strictly increasing, rows
  std::vector<int> line;                    // 1-based file line of each row
  std::vector<std::string> names;           // target channels with unit suffix
  std::vector<std::vector<double>> values;  // [target unit], names x rows
  int channel(const std::string& name) const;  // index or -1
};

// reads and validates the table and the window; throws InputError with one sentence naming the
// file, row and column: missing columns, non-numbers, time not strictly increasing, unknown or
// missing units, fewer than one gait cycle of data, a window outside the data
MeasuredLoads read_measured_loads(const MeasuredLoadSpec& spec);

// the window as one periodic gait cycle (0..100 %, every 0.25 %); `names` selects channels
// (empty: all)
Waveform cycle_waveform(const MeasuredLoads& loads, const std::vector<std::string>& names = {});

// the factor that converts `unit` into the unit of a target of `kind`; throws
// InputError (naming `where`) for an unknown unit, listing the allowed ones
double unit_factor(const std::string& kind, const std::string& unit, const std::string& where);

// the kind of a target channel from its suffix ("force", "moment", "angle", "length"), or ""
std::string channel_kind(const std::string& name);

}  // namespace kneesim::loads
