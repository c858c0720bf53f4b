#include "analysis/report/csv_columns.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace kneesim::report {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      cells.push_back(cell);
      cell.clear();
    } else if (c != '\r') {
      cell += c;
    }
  }
  cells.push_back(cell);
  return cells;
}

}  // namespace

const std::vector<double>& CsvColumns::col(const std::string& name) const {
  static const std::vector<double> none;
  const auto it = numbers.find(name);
  return it == numbers.end() ? none : it->second;
}

CsvColumns read_csv_columns(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("the report cannot read " + path.string());
  CsvColumns t;
  std::string line;
  if (!std::getline(in, line)) return t;
  t.names = split(line);
  for (const auto& n : t.names) {
    t.numbers[n];
    t.text[n];
  }
  while (std::getline(in, line)) {
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> cells = split(line);
    for (size_t i = 0; i < t.names.size(); ++i) {
      const std::string c = i < cells.size() ? cells[i] : "";
      char* end = nullptr;
      const double v = std::strtod(c.c_str(), &end);
      t.numbers[t.names[i]].push_back(!c.empty() && end && *end == '\0' ? v : std::nan(""));
      t.text[t.names[i]].push_back(c);
    }
    ++t.rows;
  }
  return t;
}

}  // namespace kneesim::report
