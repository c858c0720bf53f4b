#include "analysis/run/gait_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>

#include "analysis/report/run_report.h"
#include "analysis/run/calibrate_contact_law.h"
#include "analysis/run/fe_export.h"
#include "analysis/run/solid_outputs.h"
#include "engine/io/interrupt.h"
#include "engine/io/json_out.h"
#include "engine/io/output_folder.h"
#include "engine/io/plot.h"
#include "engine/io/progress.h"
#include "engine/simulate.h"
#include "loads/iso14243/kinematics.h"
#include "wear/wear_law.h"
#include "wear/worn_insert.h"

namespace kneesim::run {
namespace {

// removes the outputs a previous run left, so a failed run never sits next to stale results
void clear_outputs(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  if (!fs::exists(dir)) return;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == "kinematics.csv" || name == "summary.json" || name == "kinematics.png" ||
        name == "kinematics.partial.csv" || name == "measured_kinematics.csv" ||
        name == "summary.failed.json" || name == "fe_export.json" || name == "report.html" ||
        name == "fe_export.partial.json" || name == "wear_rate.partial.vtp" ||
        name.rfind("pressure_", 0) == 0 || name == "wear_rate.vtp" ||
        name.rfind("insert_stress", 0) == 0) {
      fs::remove(e.path());
    }
  }
}

io::Table make_measured_table(const loads::MeasuredKinematics& k) {
  io::Table t;
  // flexion only when the file had it (the documented 3-column form has none)
  const bool flexion = !k.flexion_deg.empty();
  t.columns = flexion ? std::vector<std::string>{"gait_pct", "flexion_deg", "ap_mm", "ie_deg"}
                      : std::vector<std::string>{"gait_pct", "ap_mm", "ie_deg"};
  for (size_t i = 0; i < k.size(); ++i) {
    if (flexion) {
      t.add_row({k.gait_pct[i], k.flexion_deg[i], k.ap_mm[i], k.ie_deg[i]});
    } else {
      t.add_row({k.gait_pct[i], k.ap_mm[i], k.ie_deg[i]});
    }
  }
  return t;
}

}  // namespace

io::Table read_measured_kinematics(const models::Config& config) {
  if (config.measured_kinematics.empty()) return {};
  // the measured pose is reported about the same femoral reference point as the simulation
  const Eigen::Vector3d p_FR_F = Eigen::Vector3d(config.femur_origin_mm[0],
                                                 config.femur_origin_mm[1],
                                                 config.femur_origin_mm[2]) * 1e-3;
  return make_measured_table(loads::read_kinematics(
      models::resolve_path(config, config.measured_kinematics),
      config.implant_kind == "mesh" ? p_FR_F : Eigen::Vector3d::Zero()));
}

std::string find_non_finite(const io::Table& table) {
  for (size_t r = 0; r < table.rows.size(); ++r) {
    for (size_t c = 0; c < table.rows[r].size(); ++c) {
      if (!std::isfinite(table.rows[r][c])) {
        return table.columns[c] + " = " + std::to_string(table.rows[r][c]) + " in row " +
               std::to_string(r + 1) + " of kinematics.csv";
      }
    }
  }
  return "";
}

models::Config load_run_config(const std::string& path, const std::vector<std::string>& sets) {
  std::vector<models::Override> overrides;
  for (const auto& s : sets) overrides.push_back(models::parse_override(s));
  return models::load_config(path, overrides);
}

engine::RunResult simulate_gait(models::BuiltModel& built, const engine::RunOptions& options,
                                engine::State* final_state,
                                const std::function<void()>& before_attempt) {
  engine::State state = engine::make_initial_state(built.model);
  engine::RunResult r = engine::simulate_with_retry(built.model, state, options, built.dt_safety,
                                                    4, before_attempt);
  if (final_state) *final_state = std::move(state);
  return r;
}

GaitRunReport run_gait_job(const GaitRunJob& job) {
  namespace fs = std::filesystem;
  const fs::path& out = job.out;
  // the measured curve is read before the simulation: a bad file costs no run
  const io::Table measured = read_measured_kinematics(job.config);
  // a folder that cannot take the results, or a law the material has no coefficient for, is
  // found before the model is built (and before a contact law is calibrated on first use,
  // which costs a deformable cycle) and the folder's old outputs are cleared
  io::check_output_folder(out);
  wear::make_wear_law(job.config.wear, job.config.material, job.config.material.friction);
  models::Config config_with_law = job.config;
  ensure_contact_law(config_with_law, job.quiet);
  const models::Config& config = config_with_law;
  models::BuiltModel built = models::build_model(config);
  if (job.on_built) job.on_built(built);
  clear_outputs(out);

  engine::RunOptions options;
  options.cycles = config.cycles;
  options.map_pcts = config.map_pcts;
  std::sort(options.map_pcts.begin(), options.map_pcts.end());
  io::ProgressBar bar("simulating");
  if (!job.quiet) options.progress = [&bar](double f) { bar.update(f); };
  // deformable insert: stress maxima and energies over the last cycle (reset by a retry)
  const bool solid = !built.model.insert_solid.empty();
  std::optional<SolidCycleTracker> tracker;
  std::optional<FeExportRecorder> fe_export;
  if (job.fe_export) {
    fe_export.emplace(built.model, job.fe_export_pcts.empty()
                                       ? find_heel_strike_and_load_peaks(built.model.gait)
                                       : job.fe_export_pcts);
  }
  // the report's 3D view: pressure and femoral pose every 2 % of the last cycle
  std::optional<report::SceneRecorder> scene;
  if (job.report) scene.emplace();
  // the wear law's depth over the last cycle: the wear-rate map of the cycle (wear.law)
  const wear::WearLawParams law =
      wear::make_wear_law(config.wear, built.material, built.model.contact.friction);
  std::optional<wear::WearAccumulator> wear_acc;
  const double last_cycle_start = (config.cycles - 1) * built.model.period;
  const std::function<void()> reset_observers = [&] {
    if (solid) {
      tracker.emplace(built.model);
      tracker->from_rest = config.cycles == 1;
    }
    if (fe_export) fe_export->clear();
    if (scene) scene->clear();
    wear_acc.emplace(wear::make_accumulator(built.model, law));
  };
  reset_observers();
  options.observer = [&](const engine::Model& m, const engine::State& s, const engine::Data& d) {
    if (solid) tracker->observe(d);
    if (fe_export) fe_export->observe(m, s, d);
    if (scene) scene->observe(m, s, d);
    // a step ending after the last cycle's start belongs to it (the first is half a step late:
    // a step's observation is of its end state)
    if (s.time > last_cycle_start + 0.5 * m.dt) wear::observe_wear(*wear_acc, m, s, d);
  };
  const auto t0 = std::chrono::steady_clock::now();
  const double dt_estimated = built.model.dt;
  engine::State state;
  const engine::RunResult result = simulate_gait(built, options, &state, reset_observers);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  bar.finish();

  const io::Table table = make_kinematics_table(result.frames);
  nlohmann::json summary = describe_model(built, config);
  summary["cycles"] = config.cycles;
  summary["seconds"] = seconds;
  summary["seconds_per_cycle"] = seconds / config.cycles;
  summary["max_stability_ratio"] = result.max_stability_ratio;
  // a run repeated with a shorter step says so (dt_s is the step it ran with)
  summary["step_retries"] = result.step_retries;
  if (result.step_retries > 0) summary["dt_estimated_s"] = dt_estimated;
  summary["element_evaluations_per_step"] =
      static_cast<double>(result.evaluations) / std::max(1L, result.steps);
  // the solid's fields at the state the run ended in (its stresses, an inverted element)
  engine::Data data;
  if (solid) {
    data = engine::make_data(built.model);
    engine::calc_forces(built.model, state, data);
    summary.update(describe_solid_cycle(built.model, state, *tracker));
    if (!built.refined_contact_node.empty()) {
      summary["contact_outside_refined_zone"] =
          calc_share_outside_zone(*tracker, built.refined_contact_node);
    }
  }
  if (result.status != engine::StepStatus::kOk) {
    // keep what was complete, under names that cannot be mistaken for a finished run
    io::write_csv(out / "kinematics.partial.csv", table);
    summary["status"] = "failed";
    summary["failure"] = engine::to_string(result.status);
    summary["failed_at_s"] = result.failed_at;
    std::string what = engine::to_string(result.status);
    if (result.status == engine::StepStatus::kRunawayMotion && built.model.coupled_rig_step) {
      // measured: on a joint that friction alone holds, the coupled step ran away at the
      // default step where CVODE and a quarter of the step did not (validation.md, rig step)
      what += " (the coupled rig step can run away at the default step where friction alone "
              "holds the joint: repeat with --set solver.dt_safety=0.2; docs/validation.md, "
              "rig step)";
    }
    std::string kept = (out / "kinematics.partial.csv").string();
    if (result.status == engine::StepStatus::kInvertedElement) {
      // the state is the one the inversion was found in: the step stopped before moving it
      const int element = data.insert_solid.inverted_element;
      summary["inverted_element"] = element;
      what = "element " + std::to_string(element) + " of the deformable insert inverted";
      write_solid_stress_vtu(out / "insert_stress.partial.vtu", built.model, state, data,
                             *tracker);
      kept += " and " + (out / "insert_stress.partial.vtu").string();
    }
    io::write_json(out / "summary.failed.json", summary);
    std::string where = "; the frames completed so far are in " + kept;
    if (result.frames.empty()) {
      // the frames are the last cycle's: a run that stopped before it kept none, which the
      // message says rather than pointing at a table with a header only
      const int stopped_in = std::min(
          config.cycles, 1 + static_cast<int>(result.failed_at / built.model.period));
      where = "; no frame was kept: the outputs are the last cycle's (cycle " +
              std::to_string(config.cycles) + ") and the run stopped in cycle " +
              std::to_string(stopped_in) + " (--cycles " + std::to_string(stopped_in) +
              " keeps the frames up to the failure)";
      if (result.status == engine::StepStatus::kInvertedElement) {
        where += "; the insert's state is in " + (out / "insert_stress.partial.vtu").string();
      }
    }
    throw std::runtime_error(std::string("the simulation stopped at t = ") +
                             std::to_string(result.failed_at) + " s: " + what + where);
  }
  // a finished run's outputs are finite numbers: a NaN that slipped past the engine's state
  // check (e.g. in a contact figure) makes the run a failure, not a complete result
  if (const std::string bad = find_non_finite(table); !bad.empty()) {
    io::write_csv(out / "kinematics.partial.csv", table);
    summary["status"] = "failed";
    summary["failure"] = "non-finite output: " + bad;
    io::write_json(out / "summary.failed.json", summary);
    throw std::runtime_error("the run's outputs are not finite (" + bad + "); the frames are "
                             "in " + (out / "kinematics.partial.csv").string());
  }
  // the title context of the PNG plots: material, geometry, cycles
  const std::string context = built.material.name + ", new insert, last of " +
                              std::to_string(config.cycles) + " cycle" +
                              (config.cycles == 1 ? "" : "s");
  std::vector<std::string> map_plot_args = {(out / "pressure_maps.png").string(),
                                            "Contact pressure, top view: " + context};
  // the tables and maps are a finished run's only beside summary.json: a signal, a full disk
  // or any error before it leaves them as X.partial.csv / X.partial.vtp (engine/io/interrupt.h)
  io::PartialOutputs partial;
  auto partial_name = [](std::filesystem::path p) {
    const std::string ext = p.extension().string();
    return p.replace_extension(".partial" + ext);
  };
  for (const char* name : {"wear_rate.vtp", "insert_stress.vtu", "fe_export.json"}) {
    partial.add(out / name, partial_name(out / name));
  }
  for (size_t i = 0; i < result.maps.size(); ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "pressure_%03.0fpct.vtp", options.map_pcts[i]);
    partial.add(out / name, partial_name(out / name));
    map_plot_args.push_back((out / name).string());
    if (solid) {
      write_solid_pressure_map(out / name, built.model, result.maps[i], state, *tracker);
    } else {
      write_pressure_map(out / name, built.model.insert, result.maps[i]);
    }
  }
  if (solid) write_solid_stress_vtu(out / "insert_stress.vtu", built.model, state, data, *tracker);
  if (fe_export) {
    if (!fe_export->complete()) {
      throw std::logic_error("FE export: an instant of the last cycle was not reached");
    }
    io::write_json(out / "fe_export.json", make_fe_export(built, config, *fe_export));
  }
  summary.update(describe_wear_rate(built.model, *wear_acc, config));
  if (!solid) write_wear_rate_map(out / "wear_rate.vtp", built.model.insert, *wear_acc);
  GaitRunReport report;
  report.figures = calc_cycle_figures(result.frames);
  report.seconds = seconds;
  summary.update(describe_figures(report.figures));
  summary["status"] = "complete";
  partial.add(out / "kinematics.csv", out / "kinematics.partial.csv");
  io::write_csv(out / "kinematics.csv", table);
  std::vector<std::string> plot_args = {(out / "kinematics.csv").string(),
                                        (out / "kinematics.png").string()};
  if (!measured.columns.empty()) {
    io::write_csv(out / "measured_kinematics.csv", measured);
    plot_args.push_back("--measured");
    plot_args.push_back((out / "measured_kinematics.csv").string());
  }
  plot_args.push_back("--context");
  plot_args.push_back(context);
  if (job.plots) io::run_plot("kinematics.py", plot_args);
  // the rigid insert's maps (the deformable insert's are per node: ParaView)
  if (job.plots && !solid && !result.maps.empty()) io::run_plot("pressure_maps.py", map_plot_args);
  // a plot that finds the disk full fails the run like any other write (exit 1, partial names)
  if (job.plots) io::wait_for_plots(/*disk_full_is_error=*/true);
  io::write_json(out / "summary.json", summary);  // its presence marks a complete run
  partial.commit();
  // the report reads the files just written, so it shows what they say
  if (job.report) report::write_run_report(out, *job.report, scene->make_scene(built));
  report.summary = std::move(summary);
  return report;
}

}  // namespace kneesim::run
