// `kneesim compare`: the same wear simulation for several insert materials, run concurrently
// (one material per core), with a comparison table, a markdown report and plots.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <mutex>

#include "analysis/run/material_comparison.h"
#include "analysis/report/provenance.h"
#include "analysis/report/wear_report.h"
#include "analysis/run/run_outputs.h"
#include "analysis/run/calibrate_contact_law.h"
#include "analysis/run/wear_job.h"
#include "wear/wear_law.h"
#include "engine/errors.h"
#include "engine/io/atomic_file.h"
#include "engine/io/json_out.h"
#include "engine/io/plot.h"
#include "engine/io/table.h"
#include "models/config.h"
#include "engine/io/output_folder.h"
#include "tools/kneesim/commands.h"

namespace kneesim::cli {
namespace {

struct CompareArgs {
  std::string config;
  std::string out = "kneesim-compare";
  std::vector<std::string> materials{"uhmwpe", "peek", "cfr-peek"};
  long cycles = 5'000'000;
  long update_every = 250'000;
  std::vector<std::string> sets;
  int jobs = 0;
  bool quiet = false;
  bool no_calibrate = false;
  bool resume = false;
  bool no_plots = false;
  bool no_report = false;
  bool no_break_even = false;
  bool break_even = false;        // also with the deformable insert
  std::string reference = "uhmwpe";
  std::string wear_law;                 // "" = the config's wear.law
  std::vector<std::string> law_params;  // name=value
};

void run(const CompareArgs& a) {
  namespace fs = std::filesystem;
  std::vector<models::Override> base;
  for (const auto& s : with_no_calibrate(a.sets, a.no_calibrate)) {
    base.push_back(models::parse_override(s));
  }
  for (auto& o : wear::wear_law_overrides(a.wear_law, a.law_params)) base.push_back(o);
  // every material is checked before any simulation starts
  std::vector<run::WearJob> jobs;
  // the report: each material's page and its 3D scene for the comparison's page
  std::optional<report::Provenance> provenance;
  std::vector<report::Scene3D> scenes(a.materials.size());
  for (const auto& m : a.materials) {
    std::vector<models::Override> o = base;
    o.push_back({"material.name", "\"" + m + "\""});
    run::WearJob job;
    job.config = models::load_config(a.config, o);
    job.cycles = a.cycles;
    job.update_every = a.update_every;
    job.out = fs::path(a.out) / m;
    job.quiet = true;
    job.depth_maps = false;
    job.plots = !a.no_plots;
    job.resume = a.resume;
    if (!a.no_report) {
      if (!provenance) provenance = report::make_provenance(a.config, a.sets, job.config);
      job.report = *provenance;
      job.scene_out = &scenes[jobs.size()];
    }
    // what defines this material's run: the config's text, the overrides, the material and
    // the schedule (a checkpoint or finished run of anything else is not resumed)
    std::ostringstream id;
    id << "compare v3\n" << (a.config.empty() ? std::string() : io::read_file(a.config)) << "\n";
    for (const auto& s : base) id << s.key << "=" << s.value << "\n";
    id << m << " " << a.cycles << " " << a.update_every;
    job.identity_text = id.str();
    run::check_wear_job(job);
    jobs.push_back(std::move(job));
  }
  // each material's calibrated law once every material is checked (first use: calibrated now,
  // before any wear run starts)
  for (size_t i = 0; i < jobs.size(); ++i) {
    run::ensure_contact_law(jobs[i].config, a.quiet);
    if (const std::string& w = jobs[i].config.contact_law_resolution.warning; !w.empty()) {
      std::fprintf(stderr, "warning: %s: %s\n", a.materials[i].c_str(), w.c_str());
    }
  }
  // the folder holds this comparison only: a previous one's table, plots and the result
  // folders of materials not run now go (a folder with anything but wear outputs stays)
  for (const char* f : {"comparison.csv", "comparison.md", "comparison.json", "compare_wear.png",
                        "compare_kinematics.png", "compare_contact.png", "break_even.csv",
                        "break_even_runs.csv", "compare_break_even.png", "report.html"}) {
    fs::remove(fs::path(a.out) / f);
  }
  std::vector<fs::path> others;
  for (const auto& e : fs::directory_iterator(a.out)) {
    const std::string name = e.path().filename().string();
    if (e.is_directory() &&
        std::find(a.materials.begin(), a.materials.end(), name) == a.materials.end()) {
      others.push_back(e.path());
    }
  }
  for (const fs::path& d : others) {
    // the folder's command marker (engine/io/output_folder.h) is part of its results
    if (run::clear_wear_outputs(d)) {
      std::error_code ec;
      fs::remove(d / ".kneesim-command", ec);
      if (fs::is_empty(d)) fs::remove(d);
    }
  }
  // one interpreter for the materials' plots and the comparison's, started now: it loads
  // matplotlib while the simulations run and plots each material as it finishes
  const io::PlotSession plots;
  std::mutex print;
  const std::vector<nlohmann::json> results =
      run::run_wear_jobs(jobs, a.jobs, [&](size_t i, const nlohmann::json& r) {
        if (a.quiet) return;
        std::lock_guard<std::mutex> lock(print);
        const models::MaterialConfig& mat = jobs[i].config.material;
        std::fprintf(stderr, "%s done: %.1f mm^3 in %.1f s%s\n", a.materials[i].c_str(),
                     r["volume_mm3"].get<double>(), r["seconds"].get<double>(),
                     mat.wear_factor_independent
                         ? ""
                         : " (wear factor not independent, so this volume is not a prediction: "
                           "see the break-even ratio)");
      });

  // the wear potential's unit follows the law (every material runs the same law)
  const run::WearPotentialUnit unit = run::wear_potential_unit(jobs.front().config.wear.law);
  const std::string potential = "wear_potential_" + unit.suffix;
  const std::string potential_run = "wear_potential_run_" + unit.suffix;
  io::Table t;
  t.label_name = "material";
  t.columns = {"volume_mm3",      "mass_mg",          "max_depth_mm",
               "wear_rate_mm3_per_Mc", "mean_peak_pressure_MPa", "peak_pressure_MPa",
               "ap_rom_mm",       "ie_rom_deg",        "elastic_modulus_MPa",
               "wear_factor_mm3_per_Nmm", "friction", "dt_s", "seconds", "contact_area_mm2",
               "wear_factor_independent", "stance_mean_pressure_MPa", "sliding_distance_mm",
               "cross_shear_ratio", potential, potential_run};
  // the deformable insert's stress and plastic strain (every material runs the same insert)
  const std::vector<std::string> solid_keys = {
      "von_mises_max_surface_MPa", "von_mises_max_subsurface_MPa", "plastic_strain_max_surface",
      "plastic_strain_max_subsurface"};
  const bool solid = results.front().contains(solid_keys.front());
  if (solid) t.columns.insert(t.columns.end(), solid_keys.begin(), solid_keys.end());
  nlohmann::json all;
  for (size_t i = 0; i < jobs.size(); ++i) {
    const auto& r = results[i];
    const auto& mat = jobs[i].config.material;
    t.label_column.push_back(a.materials[i]);
    std::vector<double> row = {
        r["volume_mm3"], r["mass_mg"], r["max_depth_mm"], r["wear_rate_mm3_per_Mc"],
        r["mean_peak_pressure_MPa"], r["peak_pressure_MPa"], r["ap_rom_mm"], r["ie_rom_deg"],
        mat.elastic_modulus_MPa, mat.wear_factor_mm3_per_Nmm, r["friction"], r["dt_s"],
        r["seconds"], r["contact_area_mm2"], mat.wear_factor_independent ? 1.0 : 0.0,
        r["stance_mean_pressure_MPa"], r["sliding_distance_mm"], r["cross_shear_ratio"],
        r[potential], r[potential_run]};
    if (solid) {
      for (const std::string& k : solid_keys) row.push_back(r[k].get<double>());
    }
    t.add_row(row);
    all[a.materials[i]] = r;
    all[a.materials[i]]["wear_factor_source"] = mat.wear_factor_source;
    all[a.materials[i]]["wear_factor_independent"] = mat.wear_factor_independent;
  }
  // the break-even wear-factor ratios to the reference material (rigid insert by default: a
  // deformable run costs minutes, and a solve needs several)
  const auto ref = std::find(a.materials.begin(), a.materials.end(), a.reference);
  const bool deformable = jobs.front().config.insert_kind == "deformable";
  std::vector<run::MaterialBreakEven> break_evens;
  std::vector<run::LiteratureBand> bands;
  std::string skipped;
  if (a.no_break_even) {
    skipped = "break-even not computed (--no-break-even)";
  } else if (ref == a.materials.end() || a.materials.size() < 2) {
    skipped = "break-even not computed: it needs the reference material '" + a.reference +
              "' (--reference) and another material";
  } else if (deformable && !a.break_even) {
    skipped = "break-even not computed for the deformable insert (each solve is several whole "
              "runs of minutes each): pass --break-even to compute it";
  } else {
    if (!a.quiet) std::fprintf(stderr, "solving the break-even wear-factor ratios to %s...\n",
                               a.reference.c_str());
    bands = run::read_wear_literature(run::wear_literature_path());
    run::BreakEvenSettings settings;
    settings.workers = a.jobs;
    break_evens = run::calc_break_evens(jobs, results, ref - a.materials.begin(), settings);
  }
  const std::string& law = jobs.front().config.wear.law;  // every material's
  std::ostringstream head;
  head << "# kneesim compare\n\n" << a.cycles << " cycles, geometry update every "
       << a.update_every << " cycles; same implant, rig and gait for every material; wear law "
       << law << ".\n\n";
  if (law == "material_pressure") {
    head << "Each material's wear factor depends on the contact pressure, k = k_ref (p / p_ref)^n:\n\n";
    for (const run::WearJob& j : jobs) {
      const models::MaterialConfig& m = j.config.material;
      char line[96];
      std::snprintf(line, sizeof line, "- %s: n = %g, p_ref = %g MPa: ", m.name.c_str(),
                    m.wear_pressure_exponent, m.wear_reference_pressure_MPa);
      head << line << m.wear_pressure_source << "\n";
    }
    head << "\n";
  }
  std::string md = run::make_comparison_markdown(jobs, a.materials, results, break_evens,
                                                 a.reference, bands);
  if (!skipped.empty()) md += "\n" + skipped + ".\n";
  io::write_csv(fs::path(a.out) / "comparison.csv", t);
  io::write_file_atomic(fs::path(a.out) / "comparison.md", head.str() + md);
  if (!break_evens.empty()) {
    all["break_even"] = run::break_even_json(break_evens, a.reference,
                                             results[ref - a.materials.begin()], bands);
    io::Table be;
    be.label_name = "material";
    // a break-even found as a jump of the result across the goal: the bracket's ends (both
    // columns equal the ratio otherwise; NaN where not found)
    be.columns = {"break_even_volume_ratio", "break_even_max_depth_ratio", "own_ratio",
                  "own_factor_independent", "volume_runs", "max_depth_runs",
                  "volume_ratio_low", "volume_ratio_high", "volume_jump_pct",
                  "max_depth_ratio_low", "max_depth_ratio_high", "max_depth_jump_pct"};
    const auto bracket = [](const run::BreakEven& e) -> std::array<double, 3> {
      const double nan = std::nan("");
      if (!std::isfinite(e.ratio)) return {nan, nan, nan};
      if (!e.jump && e.note.empty()) return {e.ratio, e.ratio, 0.0};
      return {e.lo, e.hi, run::jump_percent(e)};
    };
    io::Table runs;
    runs.label_name = "material";
    runs.columns = {"ratio", "wear_factor_mm3_per_Nmm", "complete", "volume_mm3", "max_depth_mm",
                    "cycles"};
    const double k_ref = jobs[ref - a.materials.begin()].config.material.wear_factor_mm3_per_Nmm;
    for (const run::MaterialBreakEven& b : break_evens) {
      be.label_column.push_back(b.material);
      const std::array<double, 3> v = bracket(b.volume), d = bracket(b.max_depth);
      be.add_row({b.volume.ratio, b.max_depth.ratio, b.own_ratio, b.own_independent ? 1.0 : 0.0,
                  static_cast<double>(b.volume.runs), static_cast<double>(b.max_depth.runs),
                  v[0], v[1], v[2], d[0], d[1], d[2]});
      for (const run::RatioRun& r : b.runs) {
        runs.label_column.push_back(b.material);
        runs.add_row({r.ratio, r.ratio * k_ref, r.complete ? 1.0 : 0.0, r.volume_mm3,
                      r.max_depth_mm, r.cycles});
      }
    }
    io::write_csv(fs::path(a.out) / "break_even.csv", be);
    io::write_csv(fs::path(a.out) / "break_even_runs.csv", runs);
  } else {
    all["break_even"] = skipped;
  }
  io::write_json(fs::path(a.out) / "comparison.json", all);
  std::vector<std::string> args = {a.out};
  for (const auto& m : a.materials) args.push_back(m);
  if (!a.no_plots) {
    io::run_plot("compare.py", args);
    if (!break_evens.empty()) {
      io::run_plot("break_even.py", {(fs::path(a.out) / "comparison.json").string(),
                                     (fs::path(a.out) / "compare_break_even.png").string()});
    }
  }
  if (provenance) report::write_compare_report(a.out, *provenance, a.materials, scenes);
  if (!a.quiet) std::printf("%s%sresults in %s\n", head.str().c_str(), md.c_str(), a.out.c_str());
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "The same wear simulation for several insert materials, concurrently (default: uhmwpe, "
      "peek, cfr-peek; 5 million cycles). Writes DIR/comparison.csv, DIR/comparison.md, "
      "DIR/comparison.json, plots (compare_wear.png, compare_kinematics.png, "
      "compare_contact.png), DIR/report.html and each material's wear outputs in DIR/<material>/, each "
      "checkpointed at every update (--resume continues a killed comparison). Per material: the "
      "figures that do not depend on the wear factor (pressures, area, sliding distance, "
      "cross-shear, wear potential; with --set insert=deformable the von Mises and "
      "plastic-strain maxima), the wear, whether the wear factor is independent "
      "(models/materials.toml), and the break-even wear-factor ratio to the reference material "
      "for equal volume and equal maximum depth (break_even.csv, compare_break_even.png with the "
      "published ranges).");
  cmd->add_option("config", args->config, "TOML config file")->check(CLI::ExistingFile);
  cmd->add_option("--materials", args->materials, "comma-separated material names")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--cycles", args->cycles, "total gait cycles, 1 to 1e9")
      ->capture_default_str()
      ->check(whole_range(1, 1e9));
  cmd->add_option("--update-every", args->update_every, "cycles per geometry update")
      ->capture_default_str()
      ->check(whole_range(1, 1e9));
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--set", args->sets, "override a config key (repeatable)");
  add_wear_law_options(cmd, args->wear_law, args->law_params);
  cmd->add_option("--jobs", args->jobs, "materials simulated at once (default: all cores)")
      ->check(whole_range(1, 1024));
  cmd->add_flag("--no-plots", args->no_plots,
                "skip the PNG plots (the CSV, JSON and Markdown results are the same)");
  cmd->add_flag("--no-report", args->no_report,
                "skip DIR/report.html and DIR/<material>/report.html (self-contained pages: "
                "key numbers, 3D wear-depth view per material and update, the materials' plots "
                "side by side, provenance)");
  cmd->add_flag("--quiet", args->quiet, "no per-material lines or table");
  cmd->add_flag("--no-break-even", args->no_break_even,
                "skip the break-even wear-factor ratios (each is several whole wear runs)");
  cmd->add_flag("--break-even", args->break_even,
                "compute the break-even ratios also for the deformable insert (minutes per run)");
  cmd->add_option("--reference", args->reference,
                  "material the break-even wear-factor ratios refer to")
      ->capture_default_str();
  add_no_calibrate_flag(cmd, args->no_calibrate);
  cmd->add_flag("--resume", args->resume,
                "continue a killed comparison: each material from its DIR/<material>/"
                "wear.checkpoint, a material that had finished from its summary.json");
  cmd->callback([args] {
    // each material runs in its own folder DIR/<material>: twice would race on its files
    for (size_t i = 0; i < args->materials.size(); ++i) {
      for (size_t k = 0; k < i; ++k) {
        if (args->materials[i] == args->materials[k]) {
          throw InputError("--materials lists '" + args->materials[i] + "' twice; allowed: "
                           "each material once (its results go to " +
                           (std::filesystem::path(args->out) / args->materials[i]).string() + ").");
        }
      }
    }
    io::check_output_folder(args->out);  // before any work
    run(*args);
  });
}

}  // namespace kneesim::cli
