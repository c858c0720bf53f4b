// `kneesim run`: simulate gait cycles of the rig and write kinematics, contact, pressure maps
// and a plot of the last cycle (the work is analysis/run/gait_run.h).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "analysis/report/provenance.h"
#include "analysis/run/calibrate_contact_law.h"
#include "analysis/run/gait_run.h"
#include "engine/io/plot.h"
#include "tools/kneesim/commands.h"

namespace kneesim::cli {
namespace {

struct RunArgs {
  std::string config;
  std::string out = "kneesim-run";
  int cycles = 0;
  std::vector<std::string> sets;
  std::string measured;
  bool quiet = false;
  bool no_plots = false;
  bool no_report = false;
  bool export_fe = false;
  std::vector<double> export_fe_pcts;
  bool no_calibrate = false;
};

void run(const RunArgs& a) {
  namespace fs = std::filesystem;
  run::GaitRunJob job;
  // the contact law is calibrated on first use inside run_gait_job, after the cheap input checks
  job.config = run::load_run_config(a.config, with_no_calibrate(a.sets, a.no_calibrate));
  if (a.cycles > 0) job.config.cycles = a.cycles;
  if (!a.measured.empty()) job.config.measured_kinematics = fs::absolute(a.measured).string();
  job.out = a.out;
  job.quiet = a.quiet;
  job.plots = !a.no_plots;
  if (!a.no_report) job.report = report::make_provenance(a.config, a.sets, job.config);
  job.fe_export = a.export_fe || !a.export_fe_pcts.empty();
  job.fe_export_pcts = a.export_fe_pcts;
  const int cycles = job.config.cycles;
  // the contact law's fallback warning once the model is built (a mesh refused while building
  // is one line)
  const std::string law_warning = job.config.contact_law_resolution.warning;
  const bool quiet = a.quiet;
  job.on_built = [cycles, law_warning, quiet](const models::BuiltModel& built) {
    if (!law_warning.empty()) std::fprintf(stderr, "warning: %s\n", law_warning.c_str());
    if (!quiet) {
      const engine::Model& model = built.model;
      std::fprintf(stderr,
                   "kneesim run: %d articular elements, dt %.3g s (%ld steps per cycle, limit "
                   "%.3g s), %d cycle(s)\n",
                   model.insert.size(), model.dt, std::lround(model.period / model.dt),
                   model.dt_critical, cycles);
      if (!model.insert_solid.empty()) {
        std::fprintf(stderr,
                     "kneesim run: deformable insert, %d hex8 elements, %d nodes, mass scaled "
                     "from %.3g kg by %.3g kg\n",
                     model.insert_solid.num_elements(), model.insert_solid.num_nodes(),
                     model.insert_solid.physical_mass, model.insert_solid.added_mass);
      }
    }
  };
  // one plotting interpreter for the kinematics and pressure-map plots, loading matplotlib
  // while the cycles run
  std::optional<io::PlotSession> plots;
  if (job.plots) plots.emplace();
  const run::GaitRunReport r = run::run_gait_job(job);
  plots.reset();
  if (!a.quiet) {
    const run::CycleFigures& fig = r.figures;
    std::printf("AP ROM %.2f mm, IE ROM %.2f deg, peak pressure %.1f MPa, peak contact force "
                "%.0f N (applied %.0f N), medial share in stance %.0f %%, %.3f s per cycle\n"
                "results in %s\n",
                fig.ap_rom_mm, fig.ie_rom_deg, fig.peak_pressure_MPa, fig.peak_contact_force_N,
                fig.peak_axial_load_N, 100.0 * fig.medial_fraction_stance,
                r.seconds / cycles, job.out.string().c_str());
  }
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand(
      "run",
      "Simulate gait cycles of the force-controlled rig (default: built-in generic TKR, "
      "stanmore rig, ISO 14243-1-shaped gait, UHMWPE insert). Writes DIR/kinematics.csv (one "
      "row per 1 % of the last cycle), DIR/summary.json, DIR/pressure_<pct>pct.vtp (ParaView), "
      "DIR/kinematics.png and DIR/pressure_maps.png (unless --no-plots) and DIR/report.html "
      "(unless --no-report: key numbers, a 3D view of insert and femoral component coloured by "
      "contact pressure over the cycle, the plots and the provenance, one file that opens "
      "offline). With --set insert=deformable the insert is a hex8 solid (docs/deformable.md): "
      "the pressure maps carry node pressures and element stresses, DIR/insert_stress.vtu the "
      "von Mises maximum over the cycle and the plastic strain per element, summary.json the "
      "surface/subsurface maxima and the kinetic/internal energy ratio; an inverted element "
      "stops the run (exit 1) keeping DIR/insert_stress.partial.vtu.");
  cmd->add_option("config", args->config, "TOML config file (every key defaulted)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--cycles", args->cycles, "gait cycles (outputs from the last), 1 to 1000000")
      ->check(whole_range(1, 1e6));
  cmd->add_option("--set", args->sets,
                  "override a config key, e.g. --set rig.preset=iso --set material.name=peek "
                  "(repeatable; value in TOML syntax)");
  cmd->add_option("--measured", args->measured,
                  "measured kinematics (CSV gait_pct,ap_mm,ie_deg or .sto) to overlay in the plot");
  cmd->add_flag("--no-plots", args->no_plots,
                "skip DIR/kinematics.png and DIR/pressure_maps.png (the CSV, JSON and VTK results "
                "are the same)");
  cmd->add_flag("--no-report", args->no_report,
                "skip DIR/report.html (one self-contained page: key numbers, 3D pressure view, "
                "plots, provenance)");
  cmd->add_flag("--export-fe", args->export_fe,
                "deformable insert: write DIR/fe_export.json, the insert's hex mesh, material, "
                "the femoral mesh and per instant the femur's pose with kneesim's node pressures "
                "and element stresses, for an independent FE code "
                "(tools/scripts/ccx_crosscheck.py); instants: heel strike and the two highest "
                "axial-load peaks of the gait, or --export-fe-pcts");
  cmd->add_option("--export-fe-pcts", args->export_fe_pcts,
                  "gait % of the last cycle to export (implies --export-fe), each in [0, 100)")
      ->delimiter(',')
      ->check(finite_range(0.0, 99.999));
  cmd->add_flag("--quiet", args->quiet, "no progress or summary line");
  add_no_calibrate_flag(cmd, args->no_calibrate);
  cmd->callback([args] { run(*args); });
}

}  // namespace kneesim::cli
