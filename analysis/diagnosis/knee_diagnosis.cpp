#include "analysis/diagnosis/knee_diagnosis.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "analysis/diagnosis/text_format.h"
#include "analysis/diagnosis/diagnosis_output.h"
#include "analysis/diagnosis/kinematics_case.h"
#include "analysis/diagnosis/knee_wear_case.h"
#include "analysis/run/calibrate_contact_law.h"
#include "engine/errors.h"
#include "engine/io/json_out.h"
#include "models/build_model.h"
#include "wear/wear_loop.h"

namespace kneesim::diagnosis {
namespace {

// the approximation check: the full geometry-updating wear loop (`kneesim wear`) on the
// calibration condition under the law the extended model predicts by (KneeWearTable::loop_law:
// the config's [wear] law for the baseline and creep, the effect's law otherwise), against the
// linear prediction; creep moves no surface and is left out of both sides
nlohmann::json check_linear_wear(const DiagnosisCase& c,
                                 const DiagnosisResult& r,
                                 const KneeWearTables& tables,
                                 const std::map<std::string, models::Config>& configs,
                                 const std::string& condition, double p_ref, int updates) {
  const auto t0 = std::chrono::steady_clock::now();
  double cycles = 0.0;
  for (const auto& m : c.measured.rows) {
    if (m.group == condition) cycles = std::max(cycles, m.x);
  }
  const auto& fit = r.extended();
  const Eigen::VectorXd b = fit.params.head(1), ep = fit.params.tail(fit.params.size() - 1);
  KneeWearParams p = knee_wear_params(fit.effect, b, ep, p_ref);
  if (p.effect == Effect::creep) p.effect = Effect::none;  // the wear part
  wear::WearOptions o;
  o.total_cycles = std::max(1L, std::lround(cycles));
  o.update_every = std::max(1L, o.total_cycles / updates);
  o.law = tables.at(condition)->loop_law(p);
  const wear::WearResult w = wear::run_wear(models::build_model(configs.at(condition)), o);
  nlohmann::json j;
  j["condition"] = condition;
  j["cycles"] = static_cast<double>(o.total_cycles);
  j["updates"] = static_cast<int>(w.records.size()) - 1;
  j["law"] = std::string(wear::wear_law_name(o.law.law));
  if (w.status != engine::StepStatus::kOk || w.records.empty()) {
    j["status"] = "failed: " + w.message;
    return j;
  }
  const auto& last = w.records.back();
  const double n = last.cycles;
  const double v_lin = tables.at(condition)->volume(p, n) * 1e9;
  const double d_lin = tables.at(condition)->max_depth(p, n) * 1e3;
  j["status"] = "complete";
  j["wear_loop_volume_mm3"] = last.volume * 1e9;
  j["linear_volume_mm3"] = v_lin;
  j["volume_difference_pct"] = 100.0 * (v_lin - last.volume * 1e9) / (last.volume * 1e9);
  j["wear_loop_max_depth_mm"] = last.max_depth * 1e3;
  j["linear_max_depth_mm"] = d_lin;
  j["max_depth_difference_pct"] = 100.0 * (d_lin - last.max_depth * 1e3) / (last.max_depth * 1e3);
  j["seconds"] = seconds_since(t0);
  return j;
}

}  // namespace

KneeWearDiagnosisReport run_knee_wear_diagnosis(const KneeWearDiagnosisOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!(o.steady_state_from_cycles >= 0.0 && o.steady_state_from_cycles <= 1e9)) {
    throw InputError("command line: --steady-state-from-cycles = " +
                     std::to_string(o.steady_state_from_cycles) +
                     " is outside the allowed range [0, 1e9].");
  }
  if (o.geometry_states < 0 || o.geometry_states > 50) {
    throw InputError("command line: --geometry-states = " + std::to_string(o.geometry_states) +
                     " is outside the allowed range [0, 50].");
  }
  if (o.check_updates < 0 || o.check_updates > 100) {
    throw InputError("command line: --check-updates = " + std::to_string(o.check_updates) +
                     " is outside the allowed range [0, 100].");
  }
  const DiagnosisOptions& options = o.options;
  MeasuredData data = read_knee_wear_measured(o.measured);
  const auto configs = knee_condition_configs(data, o.config, o.sets);
  const auto t_sim = std::chrono::steady_clock::now();
  const KneeWearTables tables = make_knee_wear_tables(configs, data, o.geometry_states);
  const double sim_seconds = seconds_since(t_sim);
  KneeWearCaseOptions ko;
  ko.calibration_condition = o.calibration_condition;
  ko.steady_state_from = o.steady_state_from_cycles;
  const double p_ref = knee_reference_pressure(tables, data, ko);
  const auto c = make_knee_wear_case(std::move(data), tables, ko);
  const auto r = diagnose(c, options);
  KneeWearDiagnosisReport report;
  report.summary_line = write_diagnosis(c, r, o.out);

  const int states = tables.begin()->second->geometry_states();
  std::string md = "## Forward model and its approximation\n\n" +
                   (states > 1
                        ? "Each condition was simulated along its own wear loop (the "
                          "config's law, " +
                              std::string(wear::wear_law_name(
                                  tables.begin()->second->law().law)) +
                              ") to " +
                              fmt("%.1f", kPathVolumeMargin) + " times its largest measured "
                              "volume, one cycle recorded on the pristine insert and after each "
                              "of " + std::to_string(states - 1) + " updates (" +
                              fmt("%.1f", sim_seconds) + " s for " +
                              std::to_string(tables.size()) + " conditions); every prediction "
                              "follows that geometry path (rates interpolated in worn volume)."
                        : "Each condition was simulated once (one settling and one observed "
                          "gait cycle on the pristine insert, " + fmt("%.1f", sim_seconds) +
                              " s for " + std::to_string(tables.size()) +
                              " conditions); every prediction is wear linear in cycles on that "
                              "cycle.") +
                   "\n\n"
                   "| condition | mean contact pressure (MPa) | mean cross-shear ratio | "
                   "sum A p ds per cycle (J) |\n|---|---|---|---|\n";
  for (const auto& [name, t] : tables) {
    md += "| " + name + " | " + fmt("%.2f", t->mean_pressure() * 1e-6) + " | " +
          fmt("%.4f", t->mean_cross_shear()) + " | " + fmt("%.4g", t->work()) + " |\n";
  }
  nlohmann::json check;
  if (o.check_updates > 0) {
    const std::string cal = ko.calibration_condition.empty() ? c.measured.rows.front().group
                                                             : ko.calibration_condition;
    check = check_linear_wear(c, r, tables, configs, cal, p_ref, o.check_updates);
    io::write_json(std::filesystem::path(o.out) / "approximation_check.json", check);
    if (check["status"] == "complete") {
      md += "\nCheck against the full wear loop (`kneesim wear`, geometry updated every " +
            fmt("%.0f", check["cycles"].get<double>() / check["updates"].get<int>()) +
            " cycles, law " + check["law"].get<std::string>() + ") on condition " + cal +
            " to " + fmt("%.0f", check["cycles"].get<double>()) + " cycles: volume " +
            fmt("%.2f", check["wear_loop_volume_mm3"].get<double>()) + " mm³ (loop) vs " +
            fmt("%.2f", check["linear_volume_mm3"].get<double>()) + " mm³ (linear), " +
            fmt("%+.1f", check["volume_difference_pct"].get<double>()) + " %; maximum depth " +
            fmt("%.4f", check["wear_loop_max_depth_mm"].get<double>()) + " vs " +
            fmt("%.4f", check["linear_max_depth_mm"].get<double>()) + " mm, " +
            fmt("%+.1f", check["max_depth_difference_pct"].get<double>()) + " % (" +
            fmt("%.1f", check["seconds"].get<double>()) + " s).\n";
    } else {
      md += "\nThe check against the full wear loop did not complete: " +
            check["status"].get<std::string>() + ".\n";
    }
  }
  md += "\nTotal time " + fmt("%.1f", seconds_since(t0)) + " s.\n";
  append_report(o.out, md);
  report.conditions = tables.size();
  report.sim_seconds = sim_seconds;
  report.total_seconds = seconds_since(t0);
  report.check = check;
  return report;
}

KinematicsDiagnosisReport run_kinematics_diagnosis(const KinematicsDiagnosisOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  if (o.threads < 1 || o.threads > 256) {
    throw InputError("command line: --threads = " + std::to_string(o.threads) +
                     " is outside the allowed range [1, 256].");
  }
  if (!(o.stance_end_pct > 0.0 && o.stance_end_pct < 100.0)) {
    throw InputError("command line: --stance-end-pct = " + std::to_string(o.stance_end_pct) +
                     " is outside the allowed range (0, 100).");
  }
  const DiagnosisOptions& options = o.options;
  std::vector<models::Override> overrides;
  for (const auto& s : o.sets) overrides.push_back(models::parse_override(s));
  models::Config config = models::load_config(o.config, overrides);
  // a measured .sto carries the flexion of the measured cycle: the rig is driven by it (the
  // ISO-shaped flexion peaks at 58 deg at 73 %, the DM subject's at 53 deg at 82 %), unless
  // the config or a --set names a kinematics file already
  std::string flexion_source = "the gait file's flexion (" + config.gait_file + ")";
  const bool sto = std::filesystem::path(o.measured).extension() == ".sto";
  if (sto && config.kinematics_file.empty()) {
    overrides.push_back(models::parse_override(
        "gait.kinematics_file=\"" + std::filesystem::absolute(o.measured).string() + "\""));
    config = models::load_config(o.config, overrides);
  }
  if (!config.kinematics_file.empty()) {
    flexion_source = "the measured flexion of " + config.kinematics_file;
  }
  auto data = read_kinematics_measured(o.measured,
                                                  femoral_reference_point(config));
  // the contact law once the data are read (first use: calibrated now, a deformable cycle)
  run::ensure_contact_law(config);
  auto sim = std::make_shared<KinematicsSimulator>(config);
  sim->set_threads(o.threads);
  KinematicsCaseOptions ko;
  ko.stance_end_pct = o.stance_end_pct;
  const auto c = make_kinematics_case(std::move(data), sim, ko);
  const auto r = diagnose(c, options);
  KinematicsDiagnosisReport report;
  report.summary_line = write_diagnosis(c, r, o.out);
  const auto& e = r.extended();
  std::string md = "## Forward runs\n\nFlexion prescribed: " + flexion_source +
                   " (AP force, IE torque and axial force from the gait file).\n\n" +
                   std::to_string(sim->simulations()) +
                   " rig simulations of " + std::to_string(config.cycles) + " gait cycles each (" +
                   fmt("%.1f", sim->seconds()) + " s wall, " + std::to_string(o.threads) +
                   " at a time; model build " +
                   fmt("%.1f", sim->build_seconds()) + " s; total " +
                   fmt("%.1f", seconds_since(t0)) + " s; bootstrap " +
                   std::to_string(options.bootstrap) + " resamples).\n";
  if (e.effect != Effect::none) {
    md += "\nThe extension runs forward with `kneesim run " +
          (o.config.empty() ? std::string() : o.config + " ") +
          sim->equivalent_sets(e.effect, e.params.tail(e.params.size() - 2)) + "` (plus the "
          "command's own --set options); the offsets are not part of the model.\n";
  }
  append_report(o.out, md);
  report.simulations = sim->simulations();
  report.sim_seconds = sim->seconds();
  report.total_seconds = seconds_since(t0);
  return report;
}

}  // namespace kneesim::diagnosis
