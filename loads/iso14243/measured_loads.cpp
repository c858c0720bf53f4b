#include "loads/iso14243/measured_loads.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>

#include "engine/errors.h"
#include "loads/iso14243/text_table.h"

namespace kneesim::loads {
namespace {

struct UnitDef {
  const char* kind;
  const char* name;
  double factor;  // into the target unit of the kind (N, N m, deg, mm, s)
};

constexpr double kLbf = 4.4482216152605;  // N per pound-force (exact by definition)
const UnitDef kUnits[] = {
    {"force", "N", 1.0},         {"force", "kN", 1000.0},      {"force", "lbf", kLbf},
    {"moment", "Nm", 1.0},       {"moment", "N*m", 1.0},       {"moment", "Nmm", 1e-3},
    {"moment", "N*mm", 1e-3},    {"moment", "lbf*in", kLbf * 0.0254},
    {"angle", "deg", 1.0},       {"angle", "rad", 180.0 / std::numbers::pi},
    {"length", "mm", 1.0},       {"length", "m", 1000.0},      {"length", "cm", 10.0},
    {"length", "in", 25.4},      {"time", "s", 1.0},           {"time", "sec", 1.0},
    {"time", "ms", 1e-3},        {"time", "pct", 1.0},
};

std::string allowed_units(const std::string& kind) {
  std::string s;
  for (const UnitDef& u : kUnits) {
    if (kind == u.kind) s += (s.empty() ? "" : ", ") + std::string(u.name);
  }
  return s;
}

bool known_unit(const std::string& kind, const std::string& unit) {
  for (const UnitDef& u : kUnits) {
    if (kind == u.kind && unit == u.name) return true;
  }
  return false;
}

std::string fmt(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

// a header "PM(lbf)", "PM [lbf]" or "PM" -> ("PM", "lbf" or "")
std::pair<std::string, std::string> split_header(const std::string& h) {
  const auto open = h.find_first_of("([");
  if (open == std::string::npos || open == 0) return {h, ""};
  const char close = h[open] == '(' ? ')' : ']';
  const auto end = h.find(close, open);
  std::string name = h.substr(0, open);
  while (!name.empty() && std::isspace(static_cast<unsigned char>(name.back()))) name.pop_back();
  return {name, end == std::string::npos ? h.substr(open + 1) : h.substr(open + 1, end - open - 1)};
}

// the column of `name` (bare name or full header) or -1
int find_column(const TextTable& t, const std::string& name) {
  for (size_t i = 0; i < t.header.size(); ++i) {
    if (t.header[i] == name || split_header(t.header[i]).first == name) return static_cast<int>(i);
  }
  return -1;
}

std::string column_list(const TextTable& t) {
  std::string s;
  for (const auto& h : t.header) s += (s.empty() ? "" : ", ") + h;
  return s;
}

struct Term {
  double weight = 1.0;
  std::string column;
};

// "target = 0.9871 AM + PM - 2 * AL" -> target and terms; throws naming `where`
std::pair<std::string, std::vector<Term>> parse_channel(const std::string& text,
                                                        const std::string& where) {
  const auto eq = text.find('=');
  auto bad = [&](const std::string& why) -> InputError {
    return InputError(where + ": channel \"" + text + "\" " + why +
                      " (form: \"target_unit = 0.5 colA + colB - 2 * colC\")");
  };
  if (eq == std::string::npos) throw bad("has no '='");
  std::string target = text.substr(0, eq);
  target.erase(std::remove_if(target.begin(), target.end(),
                              [](unsigned char c) { return std::isspace(c); }),
               target.end());
  if (target.empty()) throw bad("names no target");
  std::vector<Term> terms;
  const std::string e = text.substr(eq + 1);
  size_t i = 0;
  double sign = 1.0;
  bool expect_term = true;
  while (i < e.size()) {
    const char ch = e[i];
    if (std::isspace(static_cast<unsigned char>(ch))) {
      ++i;
      continue;
    }
    if (ch == '+' || ch == '-') {
      if (!expect_term) expect_term = true;
      if (ch == '-') sign = -sign;
      ++i;
      continue;
    }
    if (!expect_term) throw bad("has two terms without '+' or '-' between them");
    Term term;
    if (std::isdigit(static_cast<unsigned char>(ch)) || ch == '.') {
      char* end = nullptr;
      term.weight = std::strtod(e.c_str() + i, &end);
      i = static_cast<size_t>(end - e.c_str());
      while (i < e.size() && std::isspace(static_cast<unsigned char>(e[i]))) ++i;
      if (i < e.size() && e[i] == '*') ++i;
      while (i < e.size() && std::isspace(static_cast<unsigned char>(e[i]))) ++i;
    }
    const size_t start = i;
    while (i < e.size() && !std::isspace(static_cast<unsigned char>(e[i])) && e[i] != '+' &&
           e[i] != '*') {
      ++i;
    }
    term.column = e.substr(start, i - start);
    if (term.column.empty()) throw bad("has a number without a column");
    term.weight *= sign;
    terms.push_back(term);
    sign = 1.0;
    expect_term = false;
  }
  if (terms.empty()) throw bad("has no columns");
  return {target, terms};
}

}  // namespace

std::string channel_kind(const std::string& name) {
  auto ends = [&](const char* s) {
    const std::string suf(s);
    return name.size() > suf.size() && name.compare(name.size() - suf.size(), suf.size(), suf) == 0;
  };
  if (ends("_Nm")) return "moment";
  if (ends("_N")) return "force";
  if (ends("_deg")) return "angle";
  if (ends("_mm")) return "length";
  return "";
}

double unit_factor(const std::string& kind, const std::string& unit, const std::string& where) {
  for (const UnitDef& u : kUnits) {
    if (kind == u.kind && unit == u.name) return u.factor;
  }
  throw InputError(where + ": '" + unit + "' is not a known " + kind + " unit (allowed: " +
                   allowed_units(kind) + ")");
}

int MeasuredLoads::channel(const std::string& name) const {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

MeasuredLoads read_measured_loads(const MeasuredLoadSpec& spec) {
  const TextTable t = read_text_table(spec.file, TextFormat::csv);
  const std::string file = display_path(spec.file);
  MeasuredLoads out;
  out.source = file;
  if (t.cells.empty()) throw InputError(file + ": row 2: the table holds no data rows.");
  const std::string rows = "rows " + std::to_string(t.line.front()) + "-" +
                           std::to_string(t.line.back());

  // time column and its unit
  const int tc = spec.time_column.empty() ? 0 : find_column(t, spec.time_column);
  if (tc < 0) {
    throw InputError(file + ": row 1, column '" + spec.time_column + "': no such column (" +
                     spec.origin + " names it as the time column; columns: " + column_list(t) + ").");
  }
  out.time_name = t.header[static_cast<size_t>(tc)];
  std::string time_unit = spec.time_unit;
  if (time_unit.empty()) {
    const auto [name, unit] = split_header(out.time_name);
    // a kneesim-style name carries the unit as its suffix: time_s, gait_pct
    const auto us = name.rfind('_');
    const std::string suffix = us == std::string::npos ? std::string() : name.substr(us + 1);
    time_unit = !unit.empty() ? unit : suffix;
  }
  if (!known_unit("time", time_unit)) {
    throw InputError(file + ": row 1, column '" + out.time_name + "': time in unknown units '" +
                     time_unit + "' (allowed: " + allowed_units("time") +
                     "; give it in the header, e.g. time(s), or as gait.measured.time_unit).");
  }
  out.percent = time_unit == "pct";
  const double time_factor = unit_factor("time", time_unit, file);
  double previous = -INFINITY;
  for (size_t r = 0; r < t.cells.size(); ++r) {
    const double v = t.number(r, static_cast<size_t>(tc)) * time_factor;
    if (!(v > previous)) {
      throw InputError(file + ": row " + std::to_string(t.line[r]) + ", column '" +
                       out.time_name + "': " + fmt(v) + " does not increase (previous row " +
                       fmt(previous) + "); time must increase strictly.");
    }
    previous = v;
    out.time.push_back(v);
    out.line.push_back(t.line[r]);
  }

  // channels: weighted sums of columns, converted into the target's unit
  for (const std::string& text : spec.channels) {
    const auto [target, terms] = parse_channel(text, spec.origin.empty() ? file : spec.origin);
    const std::string kind = channel_kind(target);
    if (kind.empty()) {
      throw InputError((spec.origin.empty() ? file : spec.origin) + ": channel \"" + text +
                       "\": target '" + target + "' has no unit suffix (allowed: _N, _Nm, _deg, _mm).");
    }
    if (out.channel(target) >= 0) {
      throw InputError((spec.origin.empty() ? file : spec.origin) + ": channel '" + target +
                       "' is defined twice.");
    }
    std::vector<double> values(t.cells.size(), 0.0);
    for (const Term& term : terms) {
      const int c = find_column(t, term.column);
      if (c < 0) {
        throw InputError(file + ": row 1, column '" + term.column + "': no such column; channel '" +
                         target + "' needs it (columns: " + column_list(t) + ").");
      }
      const std::string header = t.header[static_cast<size_t>(c)];
      auto [name, unit] = split_header(header);
      if (unit.empty()) {
        // a kneesim-style header carries its unit as a suffix: axial_force_N
        const auto us = name.rfind('_');
        if (us != std::string::npos && known_unit(kind, name.substr(us + 1))) unit = name.substr(us + 1);
      }
      if (unit.empty()) {
        const auto it = spec.units.find(kind);
        if (it == spec.units.end() || it->second.empty()) {
          throw InputError(file + ": row 1, column '" + header + "': " + kind +
                           " in unknown units: the header gives none and gait.measured." + kind +
                           "_unit is not set (allowed: " + allowed_units(kind) + ", e.g. " + name +
                           "(" + allowed_units(kind).substr(0, allowed_units(kind).find(',')) + ")).");
        }
        unit = it->second;
        if (!known_unit(kind, unit)) {
          throw InputError((spec.origin.empty() ? file : spec.origin) + ": gait.measured." + kind +
                           "_unit = \"" + unit + "\" is not a known " + kind + " unit (allowed: " +
                           allowed_units(kind) + ").");
        }
      } else if (!known_unit(kind, unit)) {
        throw InputError(file + ": row 1, column '" + header + "': " + kind + " in unknown units '" +
                         unit + "' (allowed: " + allowed_units(kind) + ").");
      }
      const double factor = term.weight * unit_factor(kind, unit, file);
      for (size_t r = 0; r < t.cells.size(); ++r) {
        values[r] += factor * t.number(r, static_cast<size_t>(c));
      }
    }
    out.names.push_back(target);
    out.values.push_back(std::move(values));
  }

  // the window: one gait cycle inside the data
  const double first = out.time.front(), last = out.time.back();
  const std::string unit_word = out.percent ? " %" : " s";
  if (spec.window.empty()) {
    out.window_start = out.percent ? 0.0 : first;
    out.window_end = out.percent ? 100.0 : last;
  } else if (spec.window.size() != 2 || !(spec.window[1] > spec.window[0])) {
    throw InputError((spec.origin.empty() ? file : spec.origin) +
                     ": gait.measured.window must be [start, end] with end > start (one gait "
                     "cycle, in the time column's unit).");
  } else {
    out.window_start = spec.window[0] * time_factor;
    out.window_end = spec.window[1] * time_factor;
  }
  if (out.percent && out.window_end - out.window_start != 100.0) {
    throw InputError((spec.origin.empty() ? file : spec.origin) + ": gait.measured.window [" +
                     fmt(out.window_start) + ", " + fmt(out.window_end) +
                     "] % is not one gait cycle (a gait-percent window spans 100 %).");
  }
  const std::string where = file + ": " + rows + ", column '" + out.time_name + "': ";
  if (last - first < out.window_end - out.window_start) {
    throw InputError(where + "the data span " + fmt(first) + " to " + fmt(last) + unit_word +
                     ", fewer than one full gait cycle (" + fmt(out.window_end - out.window_start) +
                     unit_word + ", window [" + fmt(out.window_start) + ", " +
                     fmt(out.window_end) + "]).");
  }
  if (out.window_start < first || out.window_end > last) {
    throw InputError(where + "the window [" + fmt(out.window_start) + ", " +
                     fmt(out.window_end) + "]" + unit_word + " lies outside the data (" +
                     fmt(first) + " to " + fmt(last) + unit_word + ").");
  }
  if (out.time.size() < 8) {
    throw InputError(where + std::to_string(out.time.size()) +
                     " samples are too few for a gait cycle (at least 8).");
  }
  return out;
}

Waveform cycle_waveform(const MeasuredLoads& loads, const std::vector<std::string>& names) {
  constexpr int kSteps = 400;  // every 0.25 % of the cycle
  std::vector<double> pct(kSteps + 1);
  for (int i = 0; i <= kSteps; ++i) pct[static_cast<size_t>(i)] = 100.0 * i / kSteps;
  std::vector<std::string> out_names;
  std::vector<std::vector<double>> columns;
  const double t0 = loads.window_start, span = loads.window_end - loads.window_start;
  for (size_t ch = 0; ch < loads.names.size(); ++ch) {
    if (!names.empty() && std::find(names.begin(), names.end(), loads.names[ch]) == names.end()) {
      continue;
    }
    const std::vector<double>& v = loads.values[ch];
    std::vector<double> col;
    for (double p : pct) {
      const double t = t0 + span * p / 100.0;
      // linear interpolation between the samples around t (t is inside the data)
      auto it = std::upper_bound(loads.time.begin(), loads.time.end(), t);
      const size_t hi = std::min<size_t>(static_cast<size_t>(it - loads.time.begin()), v.size() - 1);
      const size_t lo = hi == 0 ? 0 : hi - 1;
      const double dt = loads.time[hi] - loads.time[lo];
      const double s = dt > 0.0 ? std::clamp((t - loads.time[lo]) / dt, 0.0, 1.0) : 0.0;
      col.push_back(v[lo] + s * (v[hi] - v[lo]));
    }
    // periodic: remove the linear drift between the cycle's ends
    const double drift = col.back() - col.front();
    for (size_t i = 0; i < col.size(); ++i) col[i] -= drift * pct[i] / 100.0;
    out_names.push_back(loads.names[ch]);
    columns.push_back(std::move(col));
  }
  return Waveform::from_table(out_names, pct, columns,
                              loads.source + " [" + fmt(loads.window_start) + ", " +
                                  fmt(loads.window_end) + (loads.percent ? "] %" : "] s"));
}

}  // namespace kneesim::loads
