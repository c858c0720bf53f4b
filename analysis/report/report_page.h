// One self-contained HTML page (report.html): sections of key numbers, a 3D view, SVG plots,
// tables and the provenance, with three.js (Debian's libjs-three), its OrbitControls and the
// viewer (analysis/report/viewer.js) inlined, so the file opens offline and fetches nothing.
//
// Every key number carries the JSON pointer of the value it shows in the command's summary
// (data-key) and the factor it was shown with (data-scale): the browser test
// (tests/report/report_browser_test.py) checks what the page shows against summary.json.
// With "#selfcheck" in the address the page renders, moves the slider, measures the canvas
// and writes what it found into <pre id="kneesim-selfcheck"> (JSON), for that test.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/report/scene3d.h"
#include "analysis/report/svg_plot.h"

namespace kneesim::report {

struct KeyNumber {
  std::string pointer;   // JSON pointer into the summary, e.g. "/peak_pressure_MPa"
  std::string label;
  double value = 0.0;    // as shown: summary value x scale
  double scale = 1.0;
  std::string unit;
  int decimals = 2;
};

// the number at `pointer` of `summary` (scaled); nullopt-like: returns false when absent or
// not a number
bool add_key_number(std::vector<KeyNumber>& list, const nlohmann::json& summary,
                    const std::string& pointer, const std::string& label,
                    const std::string& unit, int decimals, double scale = 1.0);

struct InputFile {
  std::string role;      // e.g. "config", "femur mesh", "gait"
  std::string path;
  std::string sha256;    // "" when it could not be read
};

struct Provenance {
  std::string version;        // "kneesim 0.1.0"
  std::string command_line;   // as typed (arguments quoted where needed)
  std::string working_dir;
  std::string created_utc;    // ISO 8601
  std::string config_path;    // "" for the built-in defaults
  std::string config_text;    // the file's text
  std::vector<std::string> overrides;  // --set key=value, in order
  std::vector<InputFile> inputs;
};

struct TableBlock {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

class ReportPage {
 public:
  ReportPage(std::string title, std::string subtitle);
  void add_numbers(const std::string& heading, std::vector<KeyNumber> numbers);
  // side by side: one row per quantity, one column per entry (e.g. material); `columns[c][r]`
  // is row r of column c (rows matched by label; a missing one shows "-")
  void add_number_table(const std::string& heading, const std::vector<std::string>& names,
                        const std::vector<std::vector<KeyNumber>>& columns,
                        const std::string& note = "");
  // the 3D view (one per page); an empty scene adds nothing
  void set_scene(Scene3D scene);
  void add_plots(const std::string& heading, const std::vector<PlotSpec>& plots,
                 const std::string& note = "");
  void add_table(const std::string& heading, const TableBlock& table,
                 const std::string& note = "");
  void add_text(const std::string& heading, const std::string& text);  // escaped, <p>
  void add_preformatted(const std::string& heading, const std::string& text);  // <pre>
  void set_provenance(Provenance p);
  // the page; `three_dir` holds three.min.js and examples/js/controls/OrbitControls.js
  std::string html(const std::filesystem::path& three_dir) const;

 private:
  std::string title_, subtitle_;
  std::string body_;     // sections in order, before the provenance
  bool has_scene_ = false;
  Scene3D scene_;
  size_t scene_at_ = 0;  // where in body_ the 3D section goes
  Provenance prov_;
};

// Debian's libjs-three folder ($KNEESIM_THREE_DIR when set)
std::filesystem::path three_js_dir();

// writes the page atomically to `path`; without three.js the page says so in place of the
// view and one warning line goes to stderr
void write_report(const std::filesystem::path& path, const ReportPage& page);

// the current time as "2026-11-27T12:00:00Z"
std::string utc_now();

}  // namespace kneesim::report
