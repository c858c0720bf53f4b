// Reads back a table kneesim wrote (engine/io/table.h: a header of names with units, numeric
// rows, optionally a first text column) as named columns, for the report's plots.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace kneesim::report {

struct CsvColumns {
  std::vector<std::string> names;
  std::map<std::string, std::vector<double>> numbers;  // NaN where a cell is not a number
  std::map<std::string, std::vector<std::string>> text;  // every column as written
  size_t rows = 0;
  bool has(const std::string& name) const { return numbers.count(name) > 0; }
  const std::vector<double>& col(const std::string& name) const;  // empty when absent
};

// throws std::runtime_error naming the file when it cannot be read
CsvColumns read_csv_columns(const std::filesystem::path& path);

}  // namespace kneesim::report
