// `kneesim run`: simulate gait cycles of the rig and write kinematics, contact, pressure maps
// and a plot of the last cycle.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "engine/errors.h"
#include "engine/simulate.h"
#include "loads/iso14243/kinematics.h"
#include "models/build_model.h"
#include "tools/io/json_out.h"
#include "tools/io/plot.h"
#include "tools/io/progress.h"
#include "tools/kneesim/commands.h"
#include "tools/kneesim/run_outputs.h"

namespace kneesim::cli {
namespace {

struct RunArgs {
  std::string config;
  std::string out = "kneesim-run";
  int cycles = 0;
  std::vector<std::string> sets;
  std::string measured;
  bool quiet = false;
};

// removes the outputs a previous run left, so a failed run never sits next to stale results
void clear_outputs(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  if (!fs::exists(dir)) return;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == "kinematics.csv" || name == "summary.json" || name == "kinematics.png" ||
        name == "kinematics.partial.csv" || name == "measured_kinematics.csv" || name.rfind("pressure_", 0) == 0) {
      fs::remove(e.path());
    }
  }
}

io::Table make_measured_table(const loads::MeasuredKinematics& k) {
  io::Table t;
  t.columns = {"gait_pct", "flexion_deg", "ap_mm", "ie_deg"};
  for (size_t i = 0; i < k.size(); ++i) {
    t.add_row({k.gait_pct[i], k.flexion_deg[i], k.ap_mm[i], k.ie_deg[i]});
  }
  return t;
}

void run(const RunArgs& a) {
  namespace fs = std::filesystem;
  std::vector<models::Override> overrides;
  for (const auto& s : a.sets) overrides.push_back(models::parse_override(s));
  models::Config config = models::load_config(a.config, overrides);
  if (a.cycles > 0) config.cycles = a.cycles;
  if (!a.measured.empty()) config.measured_kinematics = fs::absolute(a.measured).string();
  const fs::path out(a.out);
  models::BuiltModel built = models::build_model(config);
  const engine::Model& model = built.model;
  if (!a.quiet) {
    std::fprintf(stderr,
                 "kneesim run: %d articular elements, dt %.3g s (%ld steps per cycle, limit "
                 "%.3g s), %d cycle(s)\n",
                 model.insert.size(), model.dt, std::lround(model.period / model.dt),
                 model.dt_critical, config.cycles);
  }
  clear_outputs(out);
  fs::create_directories(out);

  engine::State state = engine::make_initial_state(model);
  engine::Data data = engine::make_data(model);
  engine::RunOptions options;
  options.cycles = config.cycles;
  options.map_pcts = config.map_pcts;
  std::sort(options.map_pcts.begin(), options.map_pcts.end());
  io::ProgressBar bar("simulating");
  if (!a.quiet) options.progress = [&bar](double f) { bar.update(f); };
  const auto t0 = std::chrono::steady_clock::now();
  const engine::RunResult result = engine::simulate(model, state, data, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  bar.finish();

  const io::Table table = make_kinematics_table(result.frames);
  nlohmann::json summary = describe_model(built, config);
  summary["cycles"] = config.cycles;
  summary["seconds"] = seconds;
  summary["seconds_per_cycle"] = seconds / config.cycles;
  summary["max_stability_ratio"] = result.max_stability_ratio;
  summary["element_evaluations_per_step"] =
      static_cast<double>(result.evaluations) / std::max(1L, result.steps);
  if (result.status != engine::StepStatus::kOk) {
    // keep what was complete, under names that cannot be mistaken for a finished run
    io::write_csv(out / "kinematics.partial.csv", table);
    summary["status"] = "failed";
    summary["failure"] = engine::to_string(result.status);
    summary["failed_at_s"] = result.failed_at;
    io::write_json(out / "summary.failed.json", summary);
    throw std::runtime_error(std::string("the simulation stopped at t = ") +
                             std::to_string(result.failed_at) + " s: " +
                             engine::to_string(result.status) + "; the frames completed so far "
                             "are in " + (out / "kinematics.partial.csv").string());
  }
  for (size_t i = 0; i < result.maps.size(); ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "pressure_%03.0fpct.vtp", options.map_pcts[i]);
    write_pressure_map(out / name, model.insert, result.maps[i]);
  }
  const CycleFigures fig = calc_cycle_figures(result.frames);
  summary.update(describe_figures(fig));
  summary["status"] = "complete";
  io::write_csv(out / "kinematics.csv", table);
  std::vector<std::string> plot_args = {(out / "kinematics.csv").string(),
                                        (out / "kinematics.png").string()};
  if (!config.measured_kinematics.empty()) {
    // the measured pose is reported about the same femoral reference point as the simulation
    const Eigen::Vector3d p_FR_F = Eigen::Vector3d(config.femur_origin_mm[0],
                                                   config.femur_origin_mm[1],
                                                   config.femur_origin_mm[2]) * 1e-3;
    const loads::MeasuredKinematics measured = loads::read_kinematics(
        models::resolve_path(config, config.measured_kinematics),
        config.implant_kind == "mesh" ? p_FR_F : Eigen::Vector3d::Zero());
    io::write_csv(out / "measured_kinematics.csv", make_measured_table(measured));
    plot_args.push_back("--measured");
    plot_args.push_back((out / "measured_kinematics.csv").string());
  }
  io::run_plot("kinematics.py", plot_args);
  io::write_json(out / "summary.json", summary);  // last: its presence marks a complete run
  if (!a.quiet) {
    std::printf("AP ROM %.2f mm, IE ROM %.2f deg, peak pressure %.1f MPa, peak contact force "
                "%.0f N (applied %.0f N), medial share in stance %.0f %%, %.3f s per cycle\n"
                "results in %s\n",
                fig.ap_rom_mm, fig.ie_rom_mm, fig.peak_pressure_MPa, fig.peak_contact_force_N,
                fig.peak_axial_load_N, 100.0 * fig.medial_fraction_stance,
                seconds / config.cycles, out.string().c_str());
  }
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand(
      "run",
      "Simulate gait cycles of the force-controlled rig (default: built-in generic TKR, "
      "stanmore rig, ISO 14243-1-shaped gait, UHMWPE insert). Writes DIR/kinematics.csv (one "
      "row per 1 % of the last cycle), DIR/summary.json, DIR/pressure_<pct>pct.vtp (ParaView) "
      "and DIR/kinematics.png.");
  cmd->add_option("config", args->config, "TOML config file (every key defaulted)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--cycles", args->cycles, "gait cycles (outputs from the last)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--set", args->sets,
                  "override a config key, e.g. --set rig.preset=iso --set material.name=peek "
                  "(repeatable; value in TOML syntax)");
  cmd->add_option("--measured", args->measured,
                  "measured kinematics (CSV gait_pct,ap_mm,ie_deg or .sto) to overlay in the plot");
  cmd->add_flag("--quiet", args->quiet, "no progress or summary line");
  cmd->callback([args] { run(*args); });
}

}  // namespace kneesim::cli
