// Column tables for CSV output. Every column name carries its unit (`ap_mm`, `pressure_MPa`).
// Numbers are printed with enough digits to round-trip a double ("%.17g" would be noisy; we
// use %.10g, more than any measured quantity needs, and bit-identical across runs).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace kneesim::io {

struct Table {
  std::vector<std::string> columns;            // header names with unit suffixes
  std::vector<std::vector<double>> rows;       // rows.size() x columns.size()
  std::vector<std::string> label_column;       // optional first text column (e.g. material)
  std::string label_name;                      // its header; empty when unused

  void add_row(std::vector<double> values) { rows.push_back(std::move(values)); }
  std::string to_csv() const;
};

// writes the table as CSV atomically
void write_csv(const std::filesystem::path& path, const Table& table);

}  // namespace kneesim::io
