#include "wear/particles/height_map.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "engine/errors.h"

namespace kneesim::particles {
namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  return out;
}

bool parse_number(const std::string& s, double& v) {
  const char* b = s.c_str();
  char* e = nullptr;
  v = std::strtod(b, &e);
  while (e != nullptr && (*e == ' ' || *e == '\t' || *e == '\r')) ++e;
  return e != b && e != nullptr && *e == '\0' && std::isfinite(v);
}

}  // namespace

HeightMap read_height_map(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::ifstream in(path);
  if (!in) throw InputError(name + ": cannot open the height map file");
  HeightMap map;
  std::string line;
  int line_no = 0;
  double spacing = -1.0;
  std::vector<double> values;
  int nx = 0, ny = -1;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> cells = split_csv(line);
    if (spacing < 0.0) {
      double v = 0.0;
      if (cells.size() != 2 || cells[0] != "spacing_nm" || !parse_number(cells[1], v)) {
        throw InputError(name + ": line " + std::to_string(line_no) +
                         " must be 'spacing_nm,<value>' (the grid spacing in nm)");
      }
      if (!(v > 0.0)) {
        throw InputError(name + ": line " + std::to_string(line_no) + " spacing_nm = " +
                         cells[1] + " is not allowed; the spacing must be > 0");
      }
      spacing = v;
      continue;
    }
    if (ny < 0) ny = static_cast<int>(cells.size());
    if (static_cast<int>(cells.size()) != ny) {
      throw InputError(name + ": row " + std::to_string(nx + 1) + " (line " +
                       std::to_string(line_no) + ") has " + std::to_string(cells.size()) +
                       " values but the first row has " + std::to_string(ny) +
                       "; every row must have the same count");
    }
    for (int j = 0; j < ny; ++j) {
      double v = 0.0;
      if (!parse_number(cells[j], v)) {
        throw InputError(name + ": row " + std::to_string(nx + 1) + ", column " +
                         std::to_string(j + 1) + " value '" + cells[j] +
                         "' is not a number (heights in nm)");
      }
      values.push_back(v * 1e-9);
    }
    ++nx;
  }
  if (spacing < 0.0 || nx == 0) throw InputError(name + ": no spacing_nm line or no height rows");
  map.grid = Grid{nx, ny, spacing * 1e-9, spacing * 1e-9, true};
  check_grid(map.grid, 1, name);
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= static_cast<double>(values.size());
  for (double& v : values) v -= mean;
  map.height = std::move(values);
  return map;
}

}  // namespace kneesim::particles
