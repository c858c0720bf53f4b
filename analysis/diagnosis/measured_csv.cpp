#include "analysis/diagnosis/measured_csv.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "engine/errors.h"
#include "loads/iso14243/text_table.h"

namespace kneesim::diagnosis {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

}  // namespace

int CsvTable::column(const std::string& name) const {
  for (size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return static_cast<int>(i);
  }
  return -1;
}

int CsvTable::require(const std::string& name, const std::string& expected) const {
  const int c = column(name);
  if (c < 0) {
    // a spreadsheet in a decimal-comma locale writes ';' between cells (and 0,5 for 0.5)
    std::string separator;
    for (const char* sep : {";", "\t", "|"}) {
      for (const std::string& h : header) {
        if (separator.empty() && h.find(sep) != std::string::npos) separator = sep;
      }
    }
    const std::string hint =
        separator.empty() ? std::string()
                          : std::string(" (the header is separated by '") +
                                (separator == "\t" ? "tab" : separator) + "', not ','; kneesim "
                                "reads comma-separated values with a decimal point, e.g. "
                                "0.5, not 0,5)";
    throw InputError(source + ": row 1 (header) has no column '" + name + "'; expected columns: " +
                     expected + hint + ".");
  }
  return c;
}

double CsvTable::number(size_t row, int col, double lo, double hi) const {
  const std::string& text = cells[row][static_cast<size_t>(col)];
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  const std::string where = source + ": row " + std::to_string(lines[row]) + ", column " +
                            header[static_cast<size_t>(col)] + ": ";
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) {
    throw InputError(where + "'" + text + "' is not a number" + loads::decimal_comma_hint(text) +
                     ".");
  }
  if (v < lo || v > hi) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "value %g is outside the allowed range [%g, %g].", v, lo, hi);
    throw InputError(where + buf);
  }
  return v;
}

bool CsvTable::empty(size_t row, int col) const {
  return cells[row][static_cast<size_t>(col)].empty();
}

CsvTable read_csv_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": the file cannot be opened for reading.");
  CsvTable t;
  t.source = path;
  std::string line;
  std::string header_line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line_no == 1) loads::strip_utf8_bom(line);
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    if (t.header.empty()) {
      header_line = line;
      t.header = split(line);
      continue;
    }
    auto cells = split(line);
    if (cells.size() != t.header.size()) {
      throw InputError(path + ": row " + std::to_string(line_no) + " has " +
                       std::to_string(cells.size()) + " fields but the header has " +
                       std::to_string(t.header.size()) +
                       loads::separator_hint(header_line, line, t.header.size(), cells.size()) +
                       ".");
    }
    t.cells.push_back(std::move(cells));
    t.lines.push_back(line_no);
  }
  if (t.header.empty()) throw InputError(path + ": row 1: the file has no header row.");
  if (t.cells.empty()) throw InputError(path + ": row 2: the file has no data rows.");
  return t;
}

MeasuredData read_wear_measurements(const CsvTable& t, const std::string& expected_columns,
                                    const std::string& depth_column, double depth_max,
                                    const std::function<std::string(size_t row)>& group_of) {
  const int c_cycles = t.require("cycles", expected_columns);
  const int c_volume = t.require("volume_mm3", expected_columns);
  const int c_depth = t.column(depth_column);
  const int c_specimen = t.column("specimen");
  MeasuredData d;
  d.source = t.source;
  d.x_name = "cycles";
  for (size_t r = 0; r < t.cells.size(); ++r) {
    Measurement m;
    m.group = group_of(r);
    m.specimen = (c_specimen >= 0) ? t.cells[r][static_cast<size_t>(c_specimen)] : "";
    m.x = t.number(r, c_cycles, 0.0, 1e9);
    m.row = t.lines[r];
    m.quantity = "volume_mm3";
    m.value = t.number(r, c_volume, 0.0, 1e6);
    d.rows.push_back(m);
    if (c_depth >= 0 && !t.empty(r, c_depth)) {
      m.quantity = depth_column;
      m.value = t.number(r, c_depth, 0.0, depth_max);
      d.rows.push_back(m);
    }
  }
  std::stable_sort(d.rows.begin(), d.rows.end(), [](const Measurement& a, const Measurement& b) {
    return a.quantity == "volume_mm3" && b.quantity != "volume_mm3";
  });
  return d;
}

}  // namespace kneesim::diagnosis
