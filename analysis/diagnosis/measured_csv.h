// Reading measured-data CSV files (header row, units in the column names) with input errors
// that name the file, the row (1-based line, header = row 1), the column, the value and the
// allowed range in one sentence. Shared by every diagnosis case.
#pragma once

#include <string>
#include <vector>

namespace kneesim::diagnosis {

struct CsvTable {
  std::string source;                           // file path, for messages
  std::vector<std::string> header;              // column names
  std::vector<std::vector<std::string>> cells;  // data rows x header.size(), trimmed
  std::vector<int> lines;                       // 1-based file line of each data row

  // column index, or -1 when absent
  int column(const std::string& name) const;
  // column index; throws InputError naming the file, row 1 and the required columns
  int require(const std::string& name, const std::string& expected) const;
  // the cell as a number in [lo, hi]; throws InputError naming file, row, column and value
  double number(size_t row, int col, double lo, double hi) const;
  // true when the cell is empty (an optional value not given)
  bool empty(size_t row, int col) const;
};

// reads a comma-separated file; throws InputError for a missing file, no header, or a row
// whose field count differs from the header's
CsvTable read_csv_table(const std::string& path);

}  // namespace kneesim::diagnosis
