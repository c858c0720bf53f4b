// One rig run as a library call: a Config (file + overrides already applied) -> Model -> the
// gait cycles -> kinematics.csv, summary.json, pressure maps and the kinematics plot in `out`.
// `kneesim run` is a thin shell over run_gait_job; the studies use the same Model and figures.
#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "analysis/report/provenance.h"
#include "analysis/run/run_outputs.h"
#include "engine/io/table.h"
#include "engine/simulate.h"
#include "models/build_model.h"
#include "models/config.h"

namespace kneesim::run {

// the config file with its --set overrides ("key=value", TOML value syntax) applied;
// InputError names the file or the override
models::Config load_run_config(const std::string& path, const std::vector<std::string>& sets);

struct GaitRunJob {
  models::Config config;        // cycles, map_pcts and measured_kinematics are read from it
  std::filesystem::path out;    // output folder
  bool quiet = false;           // no progress bar
  bool plots = true;            // out/kinematics.png
  // deformable insert: export the contact problem at gait instants of the last cycle to
  // out/fe_export.json (analysis/run/fe_export.h), at fe_export_pcts or, when that is empty,
  // at heel strike and the two highest axial-load peaks of the gait
  bool fe_export = false;
  std::vector<double> fe_export_pcts;
  // writes out/report.html (analysis/report/run_report.h) with this provenance when set
  std::optional<report::Provenance> report;
  // called once the Model is built, before any step (e.g. to describe it on the terminal)
  std::function<void(const models::BuiltModel&)> on_built;
};

struct GaitRunReport {
  nlohmann::json summary;   // as written to out/summary.json
  CycleFigures figures;     // of the last cycle
  double seconds = 0.0;     // simulation wall time [s]
};

// the config's output.measured_kinematics as a table (gait_pct, [flexion_deg,] ap_mm, ie_deg),
// reported about the simulation's femoral reference point; no columns when the config names
// no file. InputError names a bad file.
io::Table read_measured_kinematics(const models::Config& config);

// the gait cycles of a run from the Model's initial state, with engine::simulate_with_retry's
// step retry at the stability limit (built.model.dt keeps the step that worked; the result
// counts the retries); shared by `kneesim run`, the studies and the diagnoses. `final_state`
// (may be null) receives the state the run ended in; `before_attempt` resets what the observer
// accumulates before each attempt
engine::RunResult simulate_gait(models::BuiltModel& built, const engine::RunOptions& options,
                                engine::State* final_state = nullptr,
                                const std::function<void()>& before_attempt = {});

// the first non-finite cell of a table ("<column> = nan in row <r> of kinematics.csv"), or ""
std::string find_non_finite(const io::Table& table);

// runs the job and writes its outputs (summary.json last: its presence marks a complete run);
// on numerical trouble writes kinematics.partial.csv and summary.failed.json and throws
// std::runtime_error with one sentence
GaitRunReport run_gait_job(const GaitRunJob& job);

}  // namespace kneesim::run
