#include "analysis/report/summary_report.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "analysis/report/csv_columns.h"
#include "analysis/report/file_hash.h"
#include "analysis/report/provenance.h"

namespace kneesim::report {
namespace {

// the numeric leaves of `j` down to two levels, as (JSON pointer, value)
void collect_numbers(const nlohmann::json& j, const std::string& at, int depth,
                     std::vector<std::pair<std::string, double>>& out) {
  if (!j.is_object()) return;
  for (auto it = j.begin(); it != j.end(); ++it) {
    std::string key = it.key();
    std::string escaped;
    for (char c : key) escaped += c == '~' ? std::string("~0") : c == '/' ? std::string("~1") : std::string(1, c);
    const std::string p = at + "/" + escaped;
    if (it->is_number() && !it->is_boolean()) {
      out.push_back({p, it->get<double>()});
    } else if (it->is_object() && depth > 1) {
      collect_numbers(*it, p, depth - 1, out);
    }
  }
}

// decimals showing about four significant digits (none for integers)
int decimals_for(double v) {
  if (v == std::floor(v) && std::abs(v) < 1e15) return 0;
  const double a = std::abs(v);
  if (a == 0.0) return 0;
  return std::clamp(3 - static_cast<int>(std::floor(std::log10(a))), 0, 8);
}

}  // namespace

Provenance make_command_provenance() {
  namespace fs = std::filesystem;
  Provenance p;
  p.version = kVersion;
  p.command_line = command_line();
  std::error_code ec;
  p.working_dir = fs::current_path(ec).string();
  p.created_utc = utc_now();
  std::istringstream words(command_line());
  std::string w;
  bool first = true;
  while (words >> w) {
    if (first) {  // the program itself
      first = false;
      continue;
    }
    if (w.size() > 1 && w.front() == '\'' && w.back() == '\'') w = w.substr(1, w.size() - 2);
    if (const auto eq = w.find('='); w.rfind("--", 0) == 0 && eq != std::string::npos) {
      w = w.substr(eq + 1);
    }
    if (w.empty() || w[0] == '-' || !fs::is_regular_file(w, ec)) continue;
    const std::string abs = fs::absolute(w).string();
    bool listed = false;
    for (const InputFile& f : p.inputs) listed = listed || f.path == abs;
    if (!listed) p.inputs.push_back({"argument", abs, sha256_file(abs)});
  }
  return p;
}

void write_summary_report(const std::filesystem::path& out, const SummaryReport& spec,
                          const Provenance& provenance) {
  nlohmann::json summary;
  {
    std::ifstream in(out / spec.summary_file);
    if (!in) throw std::runtime_error("the report cannot read " + (out / spec.summary_file).string());
    summary = nlohmann::json::parse(in);
  }
  ReportPage page(spec.title, spec.subtitle);
  std::vector<std::pair<std::string, double>> values;
  collect_numbers(summary, "", 2, values);
  std::vector<KeyNumber> numbers;
  for (const auto& [pointer, v] : values) {
    if (numbers.size() >= 60) break;
    if (v != 0.0 && std::abs(v) < 1e-4) continue;  // tiny values (wear factors): in the file
    std::string label = pointer.substr(1);
    for (char& c : label) c = c == '/' ? ' ' : c;
    numbers.push_back({pointer, label, v, 1.0, "", decimals_for(v)});
  }
  page.add_numbers("Numbers (" + spec.summary_file + "; the unit is the name's suffix)", numbers);
  std::vector<PlotSpec> plots;
  for (const CsvPlot& c : spec.plots) {
    if (!std::filesystem::exists(out / c.csv)) continue;
    const CsvColumns t = read_csv_columns(out / c.csv);
    PlotSpec p;
    p.title = c.title;
    p.x_label = c.x_label;
    p.y_label = c.y_label;
    p.y_from_zero = c.y_from_zero;
    std::vector<double> x = t.col(c.x);
    for (double& v : x) v *= c.x_scale;
    for (const auto& [col, name] : c.y) {
      if (t.has(col)) p.series.push_back({name, x, t.col(col), "", false, t.rows <= 30});
    }
    if (!p.series.empty()) plots.push_back(std::move(p));
  }
  if (!plots.empty()) page.add_plots("Plots", plots, spec.plots_note);
  for (const auto& [heading, file] : spec.tables) {
    if (!std::filesystem::exists(out / file)) continue;
    const CsvColumns t = read_csv_columns(out / file);
    TableBlock b;
    b.header = t.names;
    for (size_t r = 0; r < std::min(t.rows, spec.table_rows); ++r) {
      std::vector<std::string> row;
      for (const auto& n : t.names) row.push_back(t.text.at(n)[r]);
      b.rows.push_back(std::move(row));
    }
    page.add_table(heading + " (" + file + ")", b,
                   t.rows > spec.table_rows ? "The first " + std::to_string(spec.table_rows) +
                                                  " of " + std::to_string(t.rows) + " rows."
                                            : "");
  }
  for (const auto& [heading, file] : spec.texts) {
    std::ifstream in(out / file);
    if (!in) continue;
    std::ostringstream text;
    text << in.rdbuf();
    page.add_preformatted(heading + " (" + file + ")", text.str());
  }
  page.set_provenance(provenance);
  write_report(out / "report.html", page);
}

}  // namespace kneesim::report
