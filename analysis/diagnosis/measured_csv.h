// Reading measured-data CSV files (header row, units in the column names) with input errors
// that name the file, the row (1-based line, header = row 1), the column, the value and the
// allowed range in one sentence. Shared by every diagnosis case.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "analysis/diagnosis/diagnosis_case.h"

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

// The measurements of a wear CSV (block-on-ring, knee simulator): per row its group from
// group_of(row), the specimen column when present, cycles, volume_mm3 and, where the optional
// `depth_column` holds a value, a second measurement of that quantity in [0, depth_max].
// Volume rows come first, so the RMSE carries mm^3. Errors as CsvTable's.
MeasuredData read_wear_measurements(const CsvTable& t, const std::string& expected_columns,
                                    const std::string& depth_column, double depth_max,
                                    const std::function<std::string(size_t row)>& group_of);

}  // namespace kneesim::diagnosis
