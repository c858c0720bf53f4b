#include "analysis/study/study_outputs.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "analysis/study/statistics.h"
#include "engine/io/atomic_file.h"
#include "engine/io/interrupt.h"
#include "engine/io/json_out.h"
#include "engine/io/plot.h"

namespace kneesim::study {
namespace {

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string level_name(double p) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "p%02.0f", 100 * p);
  return buf;
}

std::string trials_csv(const StudyProblem& p, const StudyOptions& o, const StudyResult& r) {
  const bool amv = o.method == Method::kAdvancedMeanValue;
  std::string s = "index,seed";
  if (amv) s += ",point";
  for (const auto& v : p.variables) s += "," + v.key;
  for (const auto& m : p.measures) s += "," + m;
  s += ",status\n";
  for (const auto& t : r.records) {
    s += std::to_string(t.index) + "," + std::to_string(t.seed);
    if (amv) s += "," + t.point;
    for (double x : t.inputs) s += "," + num(x);
    for (double x : t.scalars) s += "," + (t.ok ? num(x) : std::string());
    std::string why = t.failure;
    for (char& c : why)
      if (c == ',' || c == '\n' || c == '"') c = ' ';
    if (t.ok) {
      s += why.empty() ? ",ok\n" : ",ok: " + why + "\n";
    } else {
      s += ",failed: " + why + "\n";
    }
  }
  return s;
}

// one envelope file: x, then p01 / p50 / p99 and the nominal of every curve in it
std::string envelope_csv(const StudyProblem& p, const StudyResult& r, const std::string& file) {
  std::vector<size_t> curves;
  for (size_t c = 0; c < p.curves.size(); ++c)
    if (p.curves[c].file == file) curves.push_back(c);
  if (curves.empty()) return "";
  const CurveSpec& first = p.curves[curves[0]];
  std::string s = first.x_name;
  for (size_t c : curves) {
    const std::string& n = p.curves[c].name;
    s += "," + n + "_p01," + n + "_p50," + n + "_p99," + n + "_nominal";
  }
  s += "\n";
  for (size_t k = 0; k < first.x.size(); ++k) {
    s += num(first.x[k]);
    for (size_t c : curves) {
      std::vector<double> v;
      for (const auto& t : r.records)
        if (t.ok && t.curves[c].size() > k) v.push_back(t.curves[c][k]);
      s += "," + num(percentile(v, 0.01)) + "," + num(percentile(v, 0.50)) + "," +
           num(percentile(v, 0.99));
      const auto& nom = r.nominal.curves;
      s += "," + (r.nominal.ok && nom.size() > c && nom[c].size() > k ? num(nom[c][k])
                                                                       : std::string());
    }
    s += "\n";
  }
  return s;
}

}  // namespace

void clear_study_outputs(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  for (const char* f : {"trials.csv", "envelopes.csv", "wear_envelopes.csv", "sensitivity.csv",
                        "summary.json", "envelopes.png", "sensitivity.png",
                        "wear_envelopes.png", "measured_kinematics.csv", "trials.partial.csv",
                        "envelopes.partial.csv", "wear_envelopes.partial.csv",
                        "sensitivity.partial.csv"}) {
    fs::remove(dir / f);
  }
}

void write_study_outputs(const StudyProblem& p, const StudyOptions& o, const StudyResult& r) {
  namespace fs = std::filesystem;
  const bool amv = o.method == Method::kAdvancedMeanValue;
  // the tables are a study's result only beside its summary.json: a signal, a full disk or
  // any error before it leaves them as *.partial.csv (engine/io/interrupt.h)
  std::set<std::string> files;
  for (const auto& c : p.curves) files.insert(c.file);
  io::PartialOutputs partial;
  std::vector<std::string> tables = {"trials.csv", "sensitivity.csv"};
  tables.insert(tables.end(), files.begin(), files.end());
  for (const std::string& f : tables) {
    fs::path kept = o.out / f;  // X.csv -> X.partial.csv
    kept.replace_extension(".partial.csv");
    partial.add(o.out / f, kept);
  }
  io::write_file_atomic(o.out / "trials.csv", trials_csv(p, o, r));

  if (!amv) {
    for (const auto& f : files) io::write_file_atomic(o.out / f, envelope_csv(p, r, f));
  }

  nlohmann::json j;
  j["method"] = method_name(o.method);
  j["seed"] = o.seed;
  j["description"] = o.description;
  if (!p.contact_law.is_null()) j["contact_law_calibration"] = p.contact_law;
  j["trials_done"] = static_cast<long>(r.records.size()) - r.failed;
  j["trials_failed"] = r.failed;
  j["trials_resumed"] = r.resumed;
  j["trials_computed"] = r.computed;
  j["seconds"] = r.seconds;
  j["trials_per_second"] = r.seconds > 0 ? static_cast<double>(r.computed) / r.seconds : 0.0;
  for (const auto& v : p.variables) {
    nlohmann::json jv;
    jv["label"] = v.label;
    jv["nominal"] = v.nominal;
    jv["distribution"] = describe(v.distribution);
    jv["truncated_mass"] = v.removed_mass;
    j["variables"][v.key] = jv;
  }
  if (r.nominal.ok) {
    for (size_t m = 0; m < p.measures.size(); ++m)
      j["nominal"][p.measures[m]] = r.nominal.scalars[m];
  }

  std::string sens = "parameter,measure,abs_corr\n";
  if (!amv) {
    for (size_t m = 0; m < p.measures.size(); ++m) {
      std::vector<double> y;
      std::vector<std::vector<double>> x(p.variables.size());
      for (const auto& t : r.records) {
        if (!t.ok) continue;
        y.push_back(t.scalars[m]);
        for (size_t v = 0; v < p.variables.size(); ++v) x[v].push_back(t.inputs[v]);
      }
      nlohmann::json jm;
      jm["mean"] = mean(y);
      jm["sd"] = sample_sd(y);
      jm["p01"] = percentile(y, 0.01);
      jm["p50"] = percentile(y, 0.50);
      jm["p99"] = percentile(y, 0.99);
      jm["n"] = y.size();
      j["measures"][p.measures[m]] = jm;
      for (size_t v = 0; v < p.variables.size(); ++v) {
        sens += p.variables[v].key + "," + p.measures[m] + "," +
                num(std::abs(pearson(x[v], y))) + "\n";
      }
    }
  } else {
    // the mean-value model of each measure from the design runs, then the corrected runs
    std::map<std::string, const TrialRecord*> by_point;
    for (const auto& t : r.records) by_point[t.point] = &t;
    const int n = static_cast<int>(p.variables.size());
    for (size_t m = 0; m < p.measures.size(); ++m) {
      std::vector<double> steps;
      for (int v = 1; v <= n; ++v) steps.push_back(r.records[v].scalars[m]);
      const MeanValueModel mv = make_mean_value_model(r.records[0].scalars[m], steps, o.amv_step);
      nlohmann::json jm;
      jm["mean_value_g0"] = mv.g0;
      jm["runs"] = n + 1 + static_cast<int>(o.amv_levels.size());
      for (double level : o.amv_levels) {
        const std::string name = level_name(level);
        const auto it = by_point.find("mpp:" + p.measures[m] + ":" + name);
        jm[name + "_mean_value"] = mean_value_percentile(mv, level);
        if (it != by_point.end() && it->second->ok) jm[name] = it->second->scalars[m];
      }
      j["measures"][p.measures[m]] = jm;
      const double norm = mv.a.norm();
      for (int v = 0; v < n; ++v) {
        sens += p.variables[v].key + "," + p.measures[m] + "," +
                num(norm > 0 ? std::abs(mv.a[v]) / norm : 0.0) + "\n";
      }
    }
  }
  io::write_file_atomic(o.out / "sensitivity.csv", sens);

  // plots (a missing matplotlib is a warning; the CSV files are complete without them)
  if (!p.measured.columns.empty()) io::write_csv(o.out / "measured_kinematics.csv", p.measured);
  std::vector<std::string> args = {(o.out).string()};
  if (!amv) io::run_plot("study.py", args, /*disk_full_is_error=*/true);
  io::write_json(o.out / "summary.json", j);
  partial.commit();
}

}  // namespace kneesim::study
