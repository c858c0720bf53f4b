#include "analysis/diagnosis/published_wear.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>

#include "analysis/diagnosis/measured_csv.h"
#include "analysis/run/calibrate_contact_law.h"
#include "engine/errors.h"
#include "engine/io/atomic_file.h"
#include "engine/io/json_out.h"
#include "engine/io/plot.h"
#include "engine/io/table.h"
#include "engine/simulate.h"
#include "models/build_model.h"
#include "wear/wear_law.h"
#include "wear/worn_insert.h"

namespace kneesim::diagnosis {
namespace {

// the cross-shear gain of the wheel-on-flat test (PMC3685199, abstract): removing a unit volume
// takes 8.473e8 work units along the principal direction and 1.321e8 across it, so a path with
// cross-shear ratio CS wears W ((1 - CS) / q_along + CS / q_across) = (W / q_along)
// (1 + (q_along / q_across - 1) CS): g = 8.473 / 1.321 - 1
constexpr double kWheelOnFlatGain = 8.473 / 1.321 - 1.0;

double parse_optional(const CsvTable& t, size_t row, int col, double lo, double hi,
                      const std::string& allowed) {
  const std::string& s = t.cells[row][col];
  if (s == "NA" || s == "na") return -1.0;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi) {
    throw InputError(t.source + ": row " + std::to_string(t.lines[row]) + ", column " +
                     t.header[col] + ": '" + s + "' is not allowed (" + allowed + ")");
  }
  return v;
}

// one condition's predicted wear rate per law [mm^3/Mc] from one settled gait cycle
std::vector<double> predict_condition(const models::Config& config,
                                      const std::vector<PublishedLaw>& laws) {
  models::BuiltModel built = models::build_model(config);
  std::vector<wear::WearLawParams> params;
  for (const PublishedLaw& law : laws) {
    std::vector<models::Override> o = law.overrides;
    models::Config c = config;
    // the law's [wear] section on the condition's config: only the wear keys differ
    const models::Config lc = models::load_config("", o);
    c.wear = lc.wear;
    wear::WearLawParams p = wear::make_wear_law(c.wear, [&] {
      models::MaterialConfig m = built.material;
      if (!law.absolute && !(m.area_wear_coefficient > 0.0)) m.area_wear_coefficient = 1.0;
      return m;
    }(), built.model.contact.friction);
    params.push_back(p);
  }
  std::vector<wear::WearAccumulator> acc;
  const auto reset = [&] {
    acc.clear();
    for (const auto& p : params) acc.push_back(wear::make_accumulator(built.model, p));
  };
  reset();
  engine::State state = engine::make_initial_state(built.model);
  engine::RunOptions ro;
  ro.cycles = 2;  // a settling cycle, then the observed one
  const double start = built.model.period;
  ro.observer = [&](const engine::Model& m, const engine::State& s, const engine::Data& d) {
    if (s.time <= start + 0.5 * m.dt) return;
    for (auto& a : acc) wear::observe_wear(a, m, s, d);
  };
  const engine::RunResult run =
      engine::simulate_with_retry(built.model, state, ro, built.dt_safety, 4, reset);
  if (run.status != engine::StepStatus::kOk) {
    throw std::runtime_error("the gait cycle stopped: " + std::string(engine::to_string(run.status)));
  }
  const std::vector<double> area = wear::calc_site_areas(built);
  std::vector<double> rates;
  for (const auto& a : acc) {
    const std::vector<double> depth = wear::calc_site_depth(built.model, a);
    double v = 0.0;
    for (size_t i = 0; i < depth.size(); ++i) v += depth[i] * area[i];
    rates.push_back(v * 1e9 * 1e6);  // m^3 per cycle -> mm^3 per Mc
  }
  return rates;
}

double rms_log_error(const std::vector<double>& pred, const std::vector<double>& meas) {
  double s = 0.0;
  for (size_t i = 0; i < pred.size(); ++i) s += std::pow(std::log(pred[i] / meas[i]), 2);
  return pred.empty() ? 0.0 : std::sqrt(s / pred.size());
}

}  // namespace

double PublishedCondition::sem() const {
  return sd > 0.0 && n >= 1 ? sd / std::sqrt(static_cast<double>(n)) : 0.0;
}

PublishedStudy read_published_study(const std::string& csv, const std::string& config) {
  const CsvTable t = read_csv_table(csv);
  const std::string expected = "condition, cycles, mean, sd, n, units[, note]";
  const int c_cond = t.require("condition", expected), c_cyc = t.require("cycles", expected);
  const int c_mean = t.require("mean", expected), c_sd = t.require("sd", expected);
  const int c_n = t.require("n", expected), c_units = t.require("units", expected);
  const int c_note = t.column("note");
  PublishedStudy s;
  s.source = csv;
  s.config_path = config;
  s.name = std::filesystem::path(csv).stem().string();
  for (size_t r = 0; r < t.cells.size(); ++r) {
    PublishedCondition c;
    c.line = t.lines[r];
    c.condition = t.cells[r][c_cond];
    if (c.condition.empty()) {
      throw InputError(csv + ": row " + std::to_string(c.line) + ", column condition: empty "
                       "(allowed: the name of a [conditions.<name>] table of " + config + ")");
    }
    c.cycles = t.number(r, c_cyc, 1.0, 1e10);
    c.mean = t.number(r, c_mean, 1e-9, 1e9);
    c.sd = parse_optional(t, r, c_sd, std::numeric_limits<double>::min(), 1e9,
                          "a positive SD, or NA when not published");
    const double n = parse_optional(t, r, c_n, 1.0, 1e6,
                                    "a number of specimens >= 1, or NA when not published");
    if (n > 0.0 && n != std::floor(n)) {
      throw InputError(csv + ": row " + std::to_string(c.line) + ", column n: '" +
                       t.cells[r][c_n] + "' is not allowed (a whole number of specimens >= 1)");
    }
    c.n = n > 0.0 ? static_cast<int>(n) : 0;
    const std::string& units = t.cells[r][c_units];
    if (units == "mm3") {  // a volume after `cycles`: its mean rate
      c.mean *= 1e6 / c.cycles;
      if (c.sd > 0.0) c.sd *= 1e6 / c.cycles;
    } else if (units != "mm3_per_Mc") {
      throw InputError(csv + ": row " + std::to_string(c.line) + ", column units: '" + units +
                       "' is not allowed (mm3_per_Mc for a wear rate, mm3 for a volume)");
    }
    if (c_note >= 0) c.note = t.cells[r][c_note];
    s.rows.push_back(c);
  }
  if (s.rows.empty()) throw InputError(csv + ": no data rows (one row per condition)");
  return s;
}

std::vector<PublishedLaw> published_laws() {
  char gain[32];
  std::snprintf(gain, sizeof gain, "%.4f", kWheelOnFlatGain);
  return {
      {"archard", {{"wear.law", "\"archard\""}},
       "k = material.wear_factor_mm3_per_Nmm (UHMWPE: Pal 2008)", true},
      {"material_pressure", {{"wear.law", "\"material_pressure\""}},
       "k = k_ref (p / p_ref)^n with the material's n and p_ref (models/materials.toml; UHMWPE "
       "n = -1 at 10 MPa: direction Mazzucco & Spector 2003, Evans 2014; magnitude Abdelgaied "
       "2011's load-independent area law), k_ref = the material's k (Pal 2008)", true},
      {"cross_shear",
       {{"wear.law", "\"cross_shear\""}, {"wear.cross_shear_gain", gain}},
       std::string("g = ") + gain + " = q_along / q_across - 1 = 8.473 / 1.321 - 1 (wheel-on-flat, "
       "PMC3685199); k of linear sliding = the material's k (Pal 2008)", true},
      {"contact_area",
       {{"wear.law", "\"contact_area\""}, {"wear.cross_shear_gain", gain}},
       std::string("f(CS) = 1 + ") + gain + " CS as cross_shear; no independent C could be read "
       "(Abdelgaied 2011): ratios only until calibrated", false},
  };
}

nlohmann::json run_published_wear(const std::vector<PublishedStudy>& studies,
                                  const std::vector<PublishedLaw>& laws,
                                  const PublishedWearOptions& o) {
  if (studies.empty()) throw InputError("command line: no --study given");
  std::vector<models::Override> common;
  for (const auto& s : o.sets) common.push_back(models::parse_override(s));
  // every condition must be a [conditions.<name>] of its config: checked before any simulation
  struct Row {
    const PublishedStudy* study;
    const PublishedCondition* c;
    models::Config config;
  };
  std::vector<Row> rows;
  for (const PublishedStudy& s : studies) {
    const models::Config base = models::load_config(s.config_path, common);
    for (const PublishedCondition& c : s.rows) {
      const auto it = base.conditions.find(c.condition);
      if (it == base.conditions.end()) {
        std::string defined;
        for (const auto& [name, list] : base.conditions) defined += (defined.empty() ? "" : ", ") + name;
        throw InputError(s.source + ": row " + std::to_string(c.line) + ", column condition: '" +
                         c.condition + "' is not a condition of " + s.config_path + " (defined: " +
                         (defined.empty() ? std::string("none") : defined) + ")");
      }
      std::vector<models::Override> ov = common;
      for (const auto& text : it->second) ov.push_back(models::parse_override(text));
      rows.push_back({&s, &c, models::load_config(s.config_path, ov)});
      run::ensure_contact_law(rows.back().config);  // a condition's own law, on first use
    }
  }
  // the calibration condition
  size_t cal = rows.size();
  for (size_t i = 0; i < rows.size(); ++i) {
    const bool study_ok = o.calibration_study.empty() || rows[i].study->name == o.calibration_study;
    const bool cond_ok =
        o.calibration_condition.empty() || rows[i].c->condition == o.calibration_condition;
    if (study_ok && cond_ok) {
      cal = i;
      break;
    }
  }
  if (cal == rows.size()) {
    throw InputError("command line: --calibrate " + o.calibration_study + ":" +
                     o.calibration_condition + " names no condition of the studies given");
  }

  // predictions per row and law
  std::vector<std::vector<double>> pred(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) pred[i] = predict_condition(rows[i].config, laws);

  nlohmann::json out;
  out["calibration"] = {{"study", rows[cal].study->name}, {"condition", rows[cal].c->condition}};
  nlohmann::json jl = nlohmann::json::array();
  for (const PublishedLaw& l : laws) {
    nlohmann::json ov = nlohmann::json::object();  // the law as --set key=value
    for (const models::Override& o : l.overrides) ov[o.key] = o.value;
    jl.push_back({{"name", l.name}, {"source", l.source}, {"absolute", l.absolute},
                  {"overrides", ov}});
  }
  out["laws"] = jl;
  nlohmann::json jr = nlohmann::json::array();
  for (size_t i = 0; i < rows.size(); ++i) {
    nlohmann::json r;
    r["study"] = rows[i].study->name;
    r["condition"] = rows[i].c->condition;
    r["measured_mm3_per_Mc"] = rows[i].c->mean;
    r["sd_mm3_per_Mc"] = rows[i].c->sd > 0.0 ? nlohmann::json(rows[i].c->sd) : nlohmann::json();
    r["n"] = rows[i].c->n > 0 ? nlohmann::json(rows[i].c->n) : nlohmann::json();
    r["held_out"] = i != cal;
    for (size_t l = 0; l < laws.size(); ++l) {
      const double scale = rows[cal].c->mean / pred[cal][l];
      r["predicted_" + laws[l].name] =
          laws[l].absolute ? nlohmann::json(pred[i][l]) : nlohmann::json();
      r["calibrated_" + laws[l].name] = pred[i][l] * scale;
    }
    r["trivial"] = rows[cal].c->mean;
    jr.push_back(r);
  }
  out["conditions"] = jr;

  // ratios within each study: every condition over the study's first
  nlohmann::json ratios = nlohmann::json::array();
  for (const PublishedStudy& s : studies) {
    size_t first = rows.size();
    for (size_t i = 0; i < rows.size(); ++i) {
      if (rows[i].study != &s) continue;
      if (first == rows.size()) {
        first = i;
        continue;
      }
      const PublishedCondition& a = *rows[first].c;
      const PublishedCondition& b = *rows[i].c;
      nlohmann::json q;
      q["study"] = s.name;
      q["ratio"] = b.condition + " / " + a.condition;
      q["measured"] = b.mean / a.mean;
      if (a.sd > 0.0 && b.sd > 0.0 && a.mean > a.sd) {
        q["measured_low"] = (b.mean - b.sd) / (a.mean + a.sd);
        q["measured_high"] = (b.mean + b.sd) / (a.mean - a.sd);
      }
      for (size_t l = 0; l < laws.size(); ++l) q[laws[l].name] = pred[i][l] / pred[first][l];
      ratios.push_back(q);
    }
  }
  out["ratios"] = ratios;

  // held-out scores of the calibrated laws and the trivial predictor, with their interval over
  // the measured means moved to the ends of their standard errors
  std::vector<size_t> uncertain;
  for (size_t i = 0; i < rows.size(); ++i)
    if (rows[i].c->sem() > 0.0) uncertain.push_back(i);
  const size_t combos = size_t{1} << std::min<size_t>(uncertain.size(), 12);
  const size_t n_pred = laws.size() + 1;  // laws, then trivial
  std::vector<double> nominal(n_pred, 0.0);
  std::vector<double> lo(n_pred, 1e300), hi(n_pred, -1e300);
  std::vector<double> gain_lo(n_pred, 1e300), gain_hi(n_pred, -1e300);
  std::vector<double> gain_t_lo(n_pred, 1e300), gain_t_hi(n_pred, -1e300);
  for (size_t m = 0; m <= combos; ++m) {  // m == combos: the nominal means
    std::vector<double> meas(rows.size());
    for (size_t i = 0; i < rows.size(); ++i) meas[i] = rows[i].c->mean;
    if (m < combos) {
      for (size_t u = 0; u < uncertain.size() && u < 12; ++u) {
        const size_t i = uncertain[u];
        meas[i] += ((m >> u) & 1 ? 1.0 : -1.0) * rows[i].c->sem();
      }
    }
    std::vector<double> score(n_pred);
    for (size_t p = 0; p < n_pred; ++p) {
      std::vector<double> pv, mv;
      for (size_t i = 0; i < rows.size(); ++i) {
        if (i == cal) continue;
        pv.push_back(p < laws.size() ? pred[i][p] * meas[cal] / pred[cal][p] : meas[cal]);
        mv.push_back(meas[i]);
      }
      score[p] = rms_log_error(pv, mv);
    }
    for (size_t p = 0; p < n_pred; ++p) {
      if (m == combos) {
        nominal[p] = score[p];
        continue;
      }
      lo[p] = std::min(lo[p], score[p]);
      hi[p] = std::max(hi[p], score[p]);
      const double g = score[0] - score[p];              // against archard (law 0)
      const double gt = score[laws.size()] - score[p];   // against the trivial predictor
      gain_lo[p] = std::min(gain_lo[p], g);
      gain_hi[p] = std::max(gain_hi[p], g);
      gain_t_lo[p] = std::min(gain_t_lo[p], gt);
      gain_t_hi[p] = std::max(gain_t_hi[p], gt);
    }
  }
  nlohmann::json scores = nlohmann::json::array();
  std::string supported = "archard";
  double best = nominal[0];
  for (size_t p = 0; p < n_pred; ++p) {
    nlohmann::json s;
    s["predictor"] = p < laws.size() ? laws[p].name : std::string("trivial");
    s["rms_log_error"] = nominal[p];
    if (!uncertain.empty()) {
      s["rms_log_error_interval"] = {lo[p], hi[p]};
      s["gain_vs_archard_interval"] = {gain_lo[p], gain_hi[p]};
      s["gain_vs_trivial_interval"] = {gain_t_lo[p], gain_t_hi[p]};
    }
    s["gain_vs_archard"] = nominal[0] - nominal[p];
    s["gain_vs_trivial"] = nominal[laws.size()] - nominal[p];
    scores.push_back(s);
    // supported: better than archard and than the trivial predictor over the whole interval
    if (p > 0 && p < laws.size() && !uncertain.empty() && gain_lo[p] > 0.0 &&
        gain_t_lo[p] > 0.0 && nominal[p] < best) {
      supported = laws[p].name;
      best = nominal[p];
    }
  }
  out["scores"] = scores;
  out["supported_law"] = supported;
  out["held_out_conditions"] = static_cast<int>(rows.size()) - 1;
  return out;
}

std::string write_published_wear(const nlohmann::json& r, const std::filesystem::path& out,
                                  bool plots) {
  namespace fs = std::filesystem;
  fs::create_directories(out);
  std::vector<std::string> laws;
  for (const auto& l : r["laws"]) laws.push_back(l["name"]);
  io::Table t;
  t.label_name = "study";
  t.columns = {"measured_mm3_per_Mc", "sd_mm3_per_Mc", "n"};
  for (const auto& l : laws) t.columns.push_back("predicted_" + l + "_mm3_per_Mc");
  for (const auto& l : laws) t.columns.push_back("calibrated_" + l + "_mm3_per_Mc");
  t.columns.push_back("trivial_mm3_per_Mc");
  const auto num = [](const nlohmann::json& v) {
    return v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>();
  };
  std::string md = "# Published knee simulator wear against the wear laws\n\n";
  md += "Calibration condition: " + r["calibration"]["study"].get<std::string>() + " " +
        r["calibration"]["condition"].get<std::string>() + " (its measured mean sets each law's "
        "coefficient for the calibrated columns; every other condition is held out).\n\n";
  md += "| study | condition | measured (mm³/Mc) |";
  for (const auto& l : laws) md += " " + l + " independent |";
  for (const auto& l : laws) md += " " + l + " calibrated |";
  md += " trivial |\n|---|---|---|";
  for (size_t i = 0; i < 2 * laws.size() + 1; ++i) md += "---|";
  md += "\n";
  char buf[128];
  for (const auto& c : r["conditions"]) {
    t.label_column.push_back(c["study"].get<std::string>() + ":" + c["condition"].get<std::string>());
    std::vector<double> row = {c["measured_mm3_per_Mc"], num(c["sd_mm3_per_Mc"]), num(c["n"])};
    md += "| " + c["study"].get<std::string>() + " | " + c["condition"].get<std::string>() + " | ";
    if (c["sd_mm3_per_Mc"].is_null()) {
      std::snprintf(buf, sizeof buf, "%.3g (SD n/a)", c["measured_mm3_per_Mc"].get<double>());
    } else {
      std::snprintf(buf, sizeof buf, "%.3g ± %.3g (n %d)", c["measured_mm3_per_Mc"].get<double>(),
                    c["sd_mm3_per_Mc"].get<double>(), c["n"].get<int>());
    }
    md += std::string(buf) + " |";
    for (const auto& l : laws) {
      const double v = num(c["predicted_" + l]);
      row.push_back(v);
      std::snprintf(buf, sizeof buf, " %.3g |", v);
      md += std::isnan(v) ? std::string(" n/a |") : std::string(buf);
    }
    for (const auto& l : laws) {
      const double v = c["calibrated_" + l];
      row.push_back(v);
      std::snprintf(buf, sizeof buf, " %.3g%s |", v, c["held_out"].get<bool>() ? "" : " (cal.)");
      md += buf;
    }
    row.push_back(c["trivial"]);
    std::snprintf(buf, sizeof buf, " %.3g |\n", c["trivial"].get<double>());
    md += buf;
    t.add_row(row);
  }
  md += "\n## Ratios between conditions (independent of every coefficient)\n\n| study | ratio | "
        "measured (range from the SDs) |";
  for (const auto& l : laws) md += " " + l + " |";
  md += "\n|---|---|---|";
  for (size_t i = 0; i < laws.size(); ++i) md += "---|";
  md += "\n";
  for (const auto& q : r["ratios"]) {
    md += "| " + q["study"].get<std::string>() + " | " + q["ratio"].get<std::string>() + " | ";
    if (q.contains("measured_low")) {
      std::snprintf(buf, sizeof buf, "%.2f (%.2f to %.2f)", q["measured"].get<double>(),
                    q["measured_low"].get<double>(), q["measured_high"].get<double>());
    } else {
      std::snprintf(buf, sizeof buf, "%.2f (no SD published)", q["measured"].get<double>());
    }
    md += std::string(buf) + " |";
    for (const auto& l : laws) {
      std::snprintf(buf, sizeof buf, " %.2f |", q[l].get<double>());
      md += buf;
    }
    md += "\n";
  }
  md += "\n## Held-out scores (calibrated laws; RMS of ln(predicted / measured))\n\n| predictor | "
        "RMS log error | interval | gain vs archard | interval | gain vs trivial | interval |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const auto& s : r["scores"]) {
    // each piece formatted into its own string (one buffer shared by the pieces of one
    // expression would be overwritten before it is read)
    const auto iv = [&s](const char* key) {
      if (!s.contains(key)) return std::string("n/a");
      char b[64];
      std::snprintf(b, sizeof b, "%.3f to %.3f", s[key][0].get<double>(), s[key][1].get<double>());
      return std::string(b);
    };
    const auto fmt = [](const char* format, double v) {
      char b[64];
      std::snprintf(b, sizeof b, format, v);
      return std::string(b);
    };
    md += "| " + s["predictor"].get<std::string>() + " | " +
          fmt("%.3f", s["rms_log_error"].get<double>()) + " | " + iv("rms_log_error_interval") +
          " | " + fmt("%+.3f", s["gain_vs_archard"].get<double>()) + " | " +
          iv("gain_vs_archard_interval") + " | " + fmt("%+.3f", s["gain_vs_trivial"].get<double>()) +
          " | " + iv("gain_vs_trivial_interval") + " |\n";
  }
  md += "\nSupported law: **" + r["supported_law"].get<std::string>() + "** (a law is "
        "supported when its gain against archard and against the trivial predictor stays "
        "positive over the whole interval from the measured SDs; else archard stays).\n\n"
        "Parameters:\n\n";
  for (const auto& l : r["laws"]) {
    md += "- " + l["name"].get<std::string>() + ": " + l["source"].get<std::string>() + "\n";
  }
  io::write_csv(out / "published_wear.csv", t);
  io::write_json(out / "summary.json", r);
  io::write_file_atomic(out / "report.md", md);
  if (plots) {
    io::run_plot("published_wear.py",
                 {(out / "published_wear.csv").string(), (out / "published_wear.png").string()});
  }
  return md;
}

}  // namespace kneesim::diagnosis
