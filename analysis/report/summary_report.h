// The report of a command without a 3D view (`study`, `bor`, `particles`, `calibrate-contact`,
// `diagnose`): every number of its summary file (JSON, read back from DIR) as key numbers, its
// result tables as SVG plots and tables, and the provenance. The command describes which
// columns to plot; the numbers come from the file alone.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "analysis/report/report_page.h"

namespace kneesim::report {

struct CsvPlot {
  std::string csv;        // file in DIR
  std::string title;
  std::string x;          // column
  std::string x_label, y_label;  // with units
  std::vector<std::pair<std::string, std::string>> y;  // column, legend name
  bool y_from_zero = false;
  double x_scale = 1.0;   // e.g. 1e-6 for cycles in millions
};

struct SummaryReport {
  std::string title, subtitle;
  std::string summary_file = "summary.json";
  std::vector<CsvPlot> plots;
  std::string plots_note;
  std::vector<std::pair<std::string, std::string>> tables;  // heading, CSV file in DIR
  size_t table_rows = 40;                                   // rows shown per table
  std::vector<std::pair<std::string, std::string>> texts;   // heading, text file in DIR
};

// the provenance of a command whose inputs are its arguments: every argument (or the value of
// an --option=value) naming an existing file is listed with its SHA-256
Provenance make_command_provenance();

// writes DIR/report.html; a listed CSV that is absent is left out
void write_summary_report(const std::filesystem::path& out, const SummaryReport& spec,
                          const Provenance& provenance);

}  // namespace kneesim::report
