#include "engine/io/table.h"

#include <cstdio>
#include <stdexcept>

#include "engine/io/atomic_file.h"

namespace kneesim::io {

std::string Table::to_csv() const {
  std::string out;
  const bool labelled = !label_name.empty();
  if (labelled) out += label_name + ",";
  for (size_t c = 0; c < columns.size(); ++c) {
    out += columns[c];
    out += (c + 1 < columns.size()) ? "," : "\n";
  }
  char buf[64];
  for (size_t r = 0; r < rows.size(); ++r) {
    if (rows[r].size() != columns.size()) {
      throw std::logic_error("table row " + std::to_string(r) + " has " +
                             std::to_string(rows[r].size()) + " values for " +
                             std::to_string(columns.size()) + " columns");
    }
    if (labelled) out += (r < label_column.size() ? label_column[r] : std::string()) + ",";
    for (size_t c = 0; c < columns.size(); ++c) {
      std::snprintf(buf, sizeof buf, "%.10g", rows[r][c]);
      out += buf;
      out += (c + 1 < columns.size()) ? "," : "\n";
    }
  }
  return out;
}

void write_csv(const std::filesystem::path& path, const Table& table) {
  write_file_atomic(path, table.to_csv());
}

}  // namespace kneesim::io
