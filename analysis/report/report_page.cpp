#include "analysis/report/report_page.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>

#include "engine/io/atomic_file.h"
#include "engine/io/source_tree.h"

namespace kneesim::report {
namespace {

// text inside <script>: "</" could end the element early
std::string script_safe(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '<' && i + 1 < s.size() && (s[i + 1] == '/' || s[i + 1] == '!')) {
      o += "<\\";
      continue;
    }
    o += s[i];
  }
  return o;
}

bool read_text(const std::filesystem::path& p, std::string& out) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return false;
  std::ostringstream s;
  s << in.rdbuf();
  out = s.str();
  return true;
}

std::string format_number(double v, int decimals) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  if (std::string(b) == "-0" || std::string(b).find_first_not_of("-0.") == std::string::npos) {
    std::snprintf(b, sizeof b, "%.*f", decimals, 0.0);
  }
  return b;
}

const char* kStyle = R"CSS(
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,"DejaVu Sans",sans-serif;margin:0;
 color:#1d1d1f;background:#f6f6f4}
header{background:#23395b;color:#fff;padding:14px 24px}
header h1{margin:0;font-size:22px;font-weight:600}
header p{margin:4px 0 0;font-size:14px;opacity:.9}
main{max-width:1240px;margin:0 auto;padding:8px 24px 40px}
section{background:#fff;border:1px solid #ddd;border-radius:6px;margin:14px 0;padding:10px 16px}
h2{font-size:17px;margin:4px 0 10px;color:#23395b}
table{border-collapse:collapse;font-size:14px}
td,th{padding:3px 10px;border-bottom:1px solid #eee;text-align:left;vertical-align:top}
th{background:#f0f2f5;font-weight:600}
td.num{text-align:right;font-variant-numeric:tabular-nums;font-weight:600}
.numbers{display:grid;grid-template-columns:repeat(auto-fill,minmax(260px,1fr));gap:6px 18px}
.kn{display:flex;justify-content:space-between;gap:8px;border-bottom:1px solid #eee;padding:3px 0;font-size:14px;overflow-wrap:anywhere}
.kn .v{font-weight:600;font-variant-numeric:tabular-nums}
.plots{display:flex;flex-wrap:wrap;gap:8px}
svg.plot{background:#fff}
svg .grid{stroke:#e6e6e6;stroke-width:1}
svg .frame{fill:none;stroke:#888;stroke-width:1}
svg .tick{font-size:11px;fill:#444}
svg .alabel{font-size:12px;fill:#222}
svg .ptitle{font-size:13px;font-weight:600;fill:#23395b}
svg .legend{font-size:11px;fill:#222}
.viewwrap{display:flex;gap:14px;flex-wrap:wrap;align-items:flex-start}
#kneesim-canvas{width:760px;height:500px;border:1px solid #ccc;background:#fafafa;display:block}
.controls{font-size:14px;display:flex;flex-direction:column;gap:10px;flex:1 1 280px;max-width:380px}
.controls input[type=range]{width:260px}
.cbar{width:260px;height:14px;border:1px solid #999}
.cbar-labels{display:flex;justify-content:space-between;width:262px;font-size:12px}
.note{font-size:13px;color:#555}
pre{background:#f4f4f4;padding:8px;font-size:12px;overflow:auto;max-height:340px}
code{font-size:12px}
#kneesim-selfcheck{display:none}
)CSS";

// collects uncaught errors and console.error calls before any other script runs (the
// self-check reports them)
const char* kErrorTrap = R"JS(
window.__kneesimErrors=[];
window.addEventListener('error',function(e){window.__kneesimErrors.push(String(e.message||e));});
(function(){var ce=console.error;console.error=function(){window.__kneesimErrors.push(
Array.prototype.map.call(arguments,String).join(' '));return ce.apply(console,arguments);};})();
)JS";

}  // namespace

bool add_key_number(std::vector<KeyNumber>& list, const nlohmann::json& summary,
                    const std::string& pointer, const std::string& label,
                    const std::string& unit, int decimals, double scale) {
  const nlohmann::json::json_pointer ptr(pointer);
  if (!summary.contains(ptr) || !summary.at(ptr).is_number()) return false;
  list.push_back({pointer, label, summary.at(ptr).get<double>() * scale, scale, unit, decimals});
  return true;
}

ReportPage::ReportPage(std::string title, std::string subtitle)
    : title_(std::move(title)), subtitle_(std::move(subtitle)) {}

void ReportPage::add_numbers(const std::string& heading, std::vector<KeyNumber> numbers) {
  std::string s = "<section><h2>" + html_escape(heading) + "</h2><div class=\"numbers\">\n";
  for (const KeyNumber& k : numbers) {
    char scale[32];
    std::snprintf(scale, sizeof scale, "%.17g", k.scale);
    s += "<div class=\"kn\"><span>" + html_escape(k.label) + "</span><span><span class=\"v\" "
         "data-key=\"" + html_escape(k.pointer) + "\" data-scale=\"" + scale + "\">" +
         format_number(k.value, k.decimals) + "</span> " + html_escape(k.unit) +
         "</span></div>\n";
  }
  s += "</div></section>\n";
  body_ += s;
}

void ReportPage::add_number_table(const std::string& heading,
                                  const std::vector<std::string>& names,
                                  const std::vector<std::vector<KeyNumber>>& columns,
                                  const std::string& note) {
  std::vector<std::pair<std::string, std::string>> rows;  // label, unit in first-seen order
  for (const auto& col : columns) {
    for (const KeyNumber& k : col) {
      bool seen = false;
      for (const auto& r : rows) seen = seen || r.first == k.label;
      if (!seen) rows.push_back({k.label, k.unit});
    }
  }
  std::string s = "<section><h2>" + html_escape(heading) + "</h2>";
  if (!note.empty()) s += "<p class=\"note\">" + html_escape(note) + "</p>";
  s += "<table><tr><th></th><th>unit</th>";
  for (const auto& n : names) s += "<th>" + html_escape(n) + "</th>";
  s += "</tr>\n";
  for (const auto& [label, unit] : rows) {
    s += "<tr><td>" + html_escape(label) + "</td><td>" + html_escape(unit) + "</td>";
    for (const auto& col : columns) {
      const KeyNumber* k = nullptr;
      for (const KeyNumber& c : col) {
        if (c.label == label) k = &c;
      }
      if (!k) {
        s += "<td class=\"num\">-</td>";
        continue;
      }
      char scale[32];
      std::snprintf(scale, sizeof scale, "%.17g", k->scale);
      s += "<td class=\"num\" data-key=\"" + html_escape(k->pointer) + "\" data-scale=\"" +
           scale + "\">" + format_number(k->value, k->decimals) + "</td>";
    }
    s += "</tr>\n";
  }
  s += "</table></section>\n";
  body_ += s;
}

void ReportPage::set_scene(Scene3D scene) {
  if (scene.empty()) return;
  scene_ = std::move(scene);
  has_scene_ = true;
  scene_at_ = body_.size();
}

void ReportPage::add_plots(const std::string& heading, const std::vector<PlotSpec>& plots,
                           const std::string& note) {
  std::string s = "<section><h2>" + html_escape(heading) + "</h2>";
  if (!note.empty()) s += "<p class=\"note\">" + html_escape(note) + "</p>";
  s += "<div class=\"plots\">\n";
  for (const PlotSpec& p : plots) s += svg_line_plot(p);
  s += "</div></section>\n";
  body_ += s;
}

void ReportPage::add_table(const std::string& heading, const TableBlock& t,
                           const std::string& note) {
  std::string s = "<section><h2>" + html_escape(heading) + "</h2>";
  if (!note.empty()) s += "<p class=\"note\">" + html_escape(note) + "</p>";
  s += "<div style=\"overflow-x:auto\"><table><tr>";
  for (const auto& h : t.header) s += "<th>" + html_escape(h) + "</th>";
  s += "</tr>\n";
  for (const auto& row : t.rows) {
    s += "<tr>";
    for (size_t i = 0; i < row.size(); ++i) {
      s += std::string(i == 0 ? "<td>" : "<td class=\"num\">") + html_escape(row[i]) + "</td>";
    }
    s += "</tr>\n";
  }
  s += "</table></div></section>\n";
  body_ += s;
}

void ReportPage::add_text(const std::string& heading, const std::string& text) {
  body_ += "<section><h2>" + html_escape(heading) + "</h2><p>" + html_escape(text) +
           "</p></section>\n";
}

void ReportPage::add_preformatted(const std::string& heading, const std::string& text) {
  body_ += "<section><h2>" + html_escape(heading) + "</h2><pre>" + html_escape(text) +
           "</pre></section>\n";
}

void ReportPage::set_provenance(Provenance p) { prov_ = std::move(p); }

std::string ReportPage::html(const std::filesystem::path& three_dir) const {
  std::string three, orbit, viewer;
  const bool have_three =
      has_scene_ && read_text(three_dir / "three.min.js", three) &&
      read_text(three_dir / "examples" / "js" / "controls" / "OrbitControls.js", orbit);
  const bool have_viewer =
      read_text(io::source_dir() / "analysis" / "report" / "viewer.js", viewer);
  if (!have_viewer) {
    throw std::runtime_error("the report viewer " +
                             (io::source_dir() / "analysis" / "report" / "viewer.js").string() +
                             " cannot be read");
  }

  std::string view;
  if (has_scene_) {
    view = "<section id=\"view3d\"><h2>3D view</h2>";
    if (have_three) {
      view += R"(<div class="viewwrap"><canvas id="kneesim-canvas" width="760" height="500"></canvas>
<div class="controls">
<label>colour by <select id="kneesim-field"></select></label>
<div><span id="kneesim-step-name"></span>: <output id="kneesim-step"></output><br>
<input type="range" id="kneesim-slider" min="0" max="0" value="0"></div>
<div><div id="kneesim-legend-title"></div><div class="cbar" id="kneesim-cbar"></div>
<div class="cbar-labels"><span id="kneesim-legend-min"></span><span id="kneesim-legend-max"></span></div>
<div class="note" id="kneesim-step-max"></div></div>
<label><input type="checkbox" id="kneesim-femur" checked> femoral component (translucent)</label>
<div class="note">drag: rotate, wheel: zoom, right-drag: pan. Frame: tibial insert (T), x anterior,
y superior, z lateral for a right knee; millimetres.</div>
</div></div>)";
      view += "<p class=\"note\">" + html_escape(scene_.note) + "</p>";
      view += "<script type=\"application/json\" id=\"kneesim-scene\">" +
              script_safe(scene_json(scene_).dump()) + "</script>";
    } else {
      view += "<p class=\"note\">The 3D view needs Debian's libjs-three (" +
              html_escape((three_dir / "three.min.js").string()) +
              " was not found when this report was written).</p>";
    }
    view += "</section>\n";
  }
  std::string body = body_;
  body.insert(scene_at_, view);

  std::string prov = "<section id=\"provenance\"><h2>Provenance</h2><table>\n";
  auto row = [&prov](const std::string& k, const std::string& v) {
    prov += "<tr><th>" + html_escape(k) + "</th><td><code>" + html_escape(v) + "</code></td></tr>\n";
  };
  row("program", prov_.version);
  row("command line", prov_.command_line);
  row("working folder", prov_.working_dir);
  row("written (UTC)", prov_.created_utc);
  row("config file", prov_.config_path.empty() ? "(none: built-in defaults)" : prov_.config_path);
  std::string sets;
  for (const auto& s : prov_.overrides) sets += (sets.empty() ? "" : "\n") + s;
  row("overrides (--set)", sets.empty() ? "(none)" : sets);
  prov += "</table>\n<h3 style=\"font-size:15px\">Input files</h3><table><tr><th>role</th>"
          "<th>file</th><th>SHA-256</th></tr>\n";
  if (prov_.inputs.empty()) prov += "<tr><td colspan=\"3\">(none)</td></tr>\n";
  for (const InputFile& f : prov_.inputs) {
    prov += "<tr><td>" + html_escape(f.role) + "</td><td><code>" + html_escape(f.path) +
            "</code></td><td><code>" + html_escape(f.sha256.empty() ? "(unreadable)" : f.sha256) +
            "</code></td></tr>\n";
  }
  prov += "</table>\n";
  if (!prov_.config_text.empty()) {
    prov += "<h3 style=\"font-size:15px\">Config file text</h3><pre>" +
            html_escape(prov_.config_text) + "</pre>\n";
  }
  prov += "</section>\n";

  std::string page = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" +
                     html_escape(title_) + "</title>\n<style>" + kStyle + "</style>\n<script>" +
                     kErrorTrap + "</script>\n</head><body>\n<header><h1>" +
                     html_escape(title_) + "</h1><p>" + html_escape(subtitle_) +
                     "</p></header>\n<main>\n" + body + prov +
                     "<pre id=\"kneesim-selfcheck\"></pre>\n</main>\n";
  if (have_three) {
    page += "<script>" + script_safe(three) + "</script>\n<script>" + script_safe(orbit) +
            "</script>\n";
  }
  page += "<script>" + script_safe(viewer) + "</script>\n</body></html>\n";
  return page;
}

std::filesystem::path three_js_dir() {
  if (const char* d = std::getenv("KNEESIM_THREE_DIR"); d && *d) return d;
  return "/usr/share/javascript/three";
}

void write_report(const std::filesystem::path& path, const ReportPage& page) {
  const std::filesystem::path dir = three_js_dir();
  if (!std::filesystem::exists(dir / "three.min.js")) {
    std::fprintf(stderr,
                 "warning: %s has no 3D view: %s is missing (Debian package libjs-three)\n",
                 path.string().c_str(), (dir / "three.min.js").string().c_str());
  }
  io::write_file_atomic(path, page.html(dir));
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char b[32];
  std::strftime(b, sizeof b, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return b;
}

}  // namespace kneesim::report
