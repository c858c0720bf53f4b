// `kneesim wear`: Sarkar-corrected Archard wear of the insert over millions of cycles with a
// geometry update every N cycles, checkpointed after every update.
#include <cstdio>
#include <sstream>

#include "analysis/report/provenance.h"
#include "analysis/run/calibrate_contact_law.h"
#include "analysis/run/wear_job.h"
#include "engine/errors.h"
#include "engine/io/atomic_file.h"
#include "engine/io/plot.h"
#include "engine/io/table.h"
#include "models/config.h"
#include "wear/wear_law.h"
#include "engine/io/output_folder.h"
#include "tools/kneesim/commands.h"

namespace kneesim::cli {
namespace {

struct WearArgs {
  std::string config;
  std::string out = "kneesim-wear";
  long cycles = 5'000'000;
  long update_every = 250'000;
  std::vector<long> schedule;
  std::string material;
  std::vector<std::string> sets;
  bool resume = false;
  bool allow_any_wear_factor = false;
  bool quiet = false;
  bool no_calibrate = false;
  bool no_depth_maps = false;
  bool no_plots = false;
  bool no_report = false;
  std::vector<long> convergence;  // update intervals of a convergence study
  std::string wear_law;                 // "" = the config's wear.law
  std::vector<std::string> law_params;  // name=value
};

// the same prediction at several update intervals, concurrently; the finest is the reference
void run_convergence(const WearArgs& a, const std::vector<models::Override>& overrides) {
  namespace fs = std::filesystem;
  std::vector<run::WearJob> jobs;
  for (long every : a.convergence) {
    run::WearJob job;
    job.config = models::load_config(a.config, overrides);
    job.cycles = a.cycles;
    job.update_every = every;
    job.interval_flag = "--convergence";
    job.out = fs::path(a.out) / ("every_" + std::to_string(every));
    job.quiet = true;
    job.depth_maps = false;
    job.plots = !a.no_plots;
    job.allow_any_wear_factor = a.allow_any_wear_factor;
    job.identity_text = "convergence " + std::to_string(every);
    run::check_wear_job(job);
    jobs.push_back(std::move(job));
  }
  // the contact law once every job is checked (first use: calibrated once, then found)
  for (run::WearJob& job : jobs) run::ensure_contact_law(job.config, a.quiet);
  const std::vector<nlohmann::json> results = run::run_wear_jobs(jobs);
  // reference: the shortest interval
  size_t ref = 0;
  for (size_t i = 1; i < jobs.size(); ++i)
    if (jobs[i].update_every < jobs[ref].update_every) ref = i;
  const double v_ref = results[ref]["volume_mm3"], d_ref = results[ref]["max_depth_mm"];
  io::Table t;
  t.columns = {"update_every", "updates", "volume_mm3", "max_depth_mm", "volume_change_pct",
               "max_depth_change_pct", "seconds"};
  std::string md = "| cycles per update | updates | volume (mm³) | max depth (mm) | volume vs "
                   "finest | depth vs finest | time (s) |\n|---|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < jobs.size(); ++i) {
    const double v = results[i]["volume_mm3"], d = results[i]["max_depth_mm"];
    const double dv = 100.0 * (v - v_ref) / v_ref, dd = 100.0 * (d - d_ref) / d_ref;
    t.add_row({static_cast<double>(jobs[i].update_every), results[i]["updates"].get<double>(), v,
               d, dv, dd, results[i]["seconds"].get<double>()});
    char line[200];
    std::snprintf(line, sizeof line, "| %ld | %d | %.2f | %.4f | %+.2f %% | %+.2f %% | %.1f |\n",
                  jobs[i].update_every, results[i]["updates"].get<int>(), v, d, dv, dd,
                  results[i]["seconds"].get<double>());
    md += line;
  }
  io::write_csv(fs::path(a.out) / "convergence.csv", t);
  io::write_file_atomic(fs::path(a.out) / "convergence.md", md);
  if (!a.quiet) std::printf("%s", md.c_str());
}

void run(const WearArgs& a) {
  std::vector<models::Override> overrides;
  for (const auto& s : with_no_calibrate(a.sets, a.no_calibrate)) {
    overrides.push_back(models::parse_override(s));
  }
  if (!a.material.empty()) overrides.push_back({"material.name", "\"" + a.material + "\""});
  for (auto& o : wear::wear_law_overrides(a.wear_law, a.law_params)) overrides.push_back(o);
  if (!a.convergence.empty()) {
    run_convergence(a, overrides);
    return;
  }
  run::WearJob job;
  job.config = models::load_config(a.config, overrides);
  job.cycles = a.cycles;
  job.update_every = a.update_every;
  job.schedule = a.schedule;
  job.out = a.out;
  job.resume = a.resume;
  job.allow_any_wear_factor = a.allow_any_wear_factor;
  job.quiet = a.quiet;
  job.depth_maps = !a.no_depth_maps;
  job.plots = !a.no_plots;
  if (!a.no_report) {
    std::vector<std::string> sets = a.sets;
    if (!a.material.empty()) sets.push_back("material.name=\"" + a.material + "\" (--material)");
    job.report = report::make_provenance(a.config, sets, job.config);
  }
  std::ostringstream id;
  id << "wear v1\n" << (a.config.empty() ? std::string() : io::read_file(a.config)) << "\n";
  for (const auto& o : overrides) id << o.key << "=" << o.value << "\n";
  id << a.cycles << " " << a.update_every;
  for (long s : a.schedule) id << " " << s;
  job.identity_text = id.str();
  run::check_wear_job(job);
  // the contact law after every cheap check (first use: calibrated now, a deformable cycle)
  run::ensure_contact_law(job.config, a.quiet);
  // the fallback warning once the model is built (a mesh refused while building is one line)
  job.on_built = [w = job.config.contact_law_resolution.warning](const models::BuiltModel&) {
    if (!w.empty()) std::fprintf(stderr, "warning: %s\n", w.c_str());
  };
  const io::PlotSession plots;  // matplotlib loads on the other core while the wear runs
  const nlohmann::json s = run::run_wear_job(job);
  if (!a.quiet) {
    std::printf("%s: %.2f mm^3 (%.2f mg) after %ld cycles, %.2f mm^3 per million cycles, max "
                "depth %.3f mm, %d updates in %.1f s\nresults in %s\n",
                s["material"].get<std::string>().c_str(), s["volume_mm3"].get<double>(),
                s["mass_mg"].get<double>(), a.cycles, s["wear_rate_mm3_per_Mc"].get<double>(),
                s["max_depth_mm"].get<double>(), s["updates"].get<int>(),
                s["seconds"].get<double>(), a.out.c_str());
  }
}

}  // namespace

void add_wear_command(CLI::App& app) {
  auto args = std::make_shared<WearArgs>();
  CLI::App* cmd = app.add_subcommand(
      "wear",
      "Archard wear with the Sarkar correction: one simulated gait cycle per geometry update, "
      "scaled by the cycles per update, the insert receding along its normal (default: 5 "
      "million cycles, update every 250 000, built-in implant, stanmore rig, UHMWPE). Writes "
      "DIR/wear.csv (one row per update), DIR/summary.json, DIR/wear_depth_<cycles>.vtp per "
      "update, DIR/final_depth.csv, DIR/wear.png, DIR/depth_map.png and DIR/report.html; checkpoints after "
      "every update (DIR/wear.checkpoint) so that --resume continues a killed run. With --set "
      "insert=deformable the hex8 insert wears (docs/deformable.md): its top nodes recede, its "
      "columns are re-graded, and wear.csv and summary.json add the von Mises and plastic-strain "
      "maxima (surface, subsurface), DIR/insert_stress.vtu and DIR/wear_surface.vtp per element.");
  cmd->add_option("config", args->config, "TOML config file")->check(CLI::ExistingFile);
  cmd->add_option("--cycles", args->cycles, "total gait cycles, 1 to 1e9")
      ->capture_default_str()
      ->check(whole_range(1, 1e9));
  cmd->add_option("--update-every", args->update_every, "cycles per geometry update")
      ->capture_default_str()
      ->check(whole_range(1, 1e9));
  cmd->add_option("--schedule", args->schedule,
                  "cycles per update as a list, the last repeated (e.g. 50000,100000,250000); "
                  "overrides --update-every")
      ->delimiter(',')
      ->check(whole_range(1, 1e9));
  cmd->add_option("--material", args->material,
                  "insert material from models/materials.toml (uhmwpe, peek, cfr-peek, ...) or "
                  "a [materials.<name>] table of the config");
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--set", args->sets, "override a config key (repeatable)");
  cmd->add_flag("--resume", args->resume, "continue from DIR/wear.checkpoint");
  cmd->add_option("--convergence", args->convergence,
                  "update-interval convergence study: run the prediction once per listed "
                  "interval (e.g. 1000000,500000,250000,100000,50000) into DIR/every_<N>/ and "
                  "write DIR/convergence.csv and .md (changes against the finest)")
      ->delimiter(',')
      ->check(whole_range(1, 1e9));
  add_wear_law_options(cmd, args->wear_law, args->law_params);
  cmd->add_flag("--allow-any-wear-factor", args->allow_any_wear_factor,
                "accept wear factors outside 1e-12..1e-6 mm^3/(N mm)");
  cmd->add_flag("--no-depth-maps", args->no_depth_maps,
                "write no DIR/wear_depth_<cycles>.vtp (a run whose maps would not fit in the "
                "free space of DIR is refused with the estimate; above 2 GB a note says so)");
  cmd->add_flag("--no-plots", args->no_plots,
                "skip DIR/wear.png and DIR/depth_map.png (the CSV, JSON and VTK results are the "
                "same)");
  cmd->add_flag("--no-report", args->no_report,
                "skip DIR/report.html (one self-contained page: key numbers, 3D wear-depth view "
                "per update, plots, provenance)");
  cmd->add_flag("--quiet", args->quiet, "no progress or summary line");
  add_no_calibrate_flag(cmd, args->no_calibrate);
  cmd->callback([args] {
    io::check_output_folder(args->out);  // before any work
    run(*args);
  });
}

}  // namespace kneesim::cli
