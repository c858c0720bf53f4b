// `kneesim compare`: the same wear simulation for several insert materials, run concurrently
// (one material per core), with a comparison table, a markdown report and plots.
#include <algorithm>
#include <cstdio>
#include <sstream>
#include <mutex>

#include "analysis/run/wear_job.h"
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
  bool resume = false;
  bool no_plots = false;
};

void run(const CompareArgs& a) {
  namespace fs = std::filesystem;
  std::vector<models::Override> base;
  for (const auto& s : a.sets) base.push_back(models::parse_override(s));
  // every material is checked before any simulation starts
  std::vector<run::WearJob> jobs;
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
    // what defines this material's run: the config's text, the overrides, the material and
    // the schedule (a checkpoint or finished run of anything else is not resumed)
    std::ostringstream id;
    id << "compare v2\n" << (a.config.empty() ? std::string() : io::read_file(a.config)) << "\n";
    for (const auto& s : a.sets) id << s << "\n";
    id << m << " " << a.cycles << " " << a.update_every;
    job.identity_text = id.str();
    run::check_wear_job(job);
    jobs.push_back(std::move(job));
  }
  // the folder holds this comparison only: a previous one's table, plots and the result
  // folders of materials not run now go (a folder with anything but wear outputs stays)
  for (const char* f : {"comparison.csv", "comparison.md", "comparison.json", "compare_wear.png",
                        "compare_kinematics.png", "compare_contact.png"}) {
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
    if (run::clear_wear_outputs(d) && fs::is_empty(d)) fs::remove(d);
  }
  // one interpreter for the materials' plots and the comparison's, started now: it loads
  // matplotlib while the simulations run and plots each material as it finishes
  const io::PlotSession plots;
  std::mutex print;
  const std::vector<nlohmann::json> results =
      run::run_wear_jobs(jobs, a.jobs, [&](size_t i, const nlohmann::json& r) {
        if (a.quiet) return;
        std::lock_guard<std::mutex> lock(print);
        std::fprintf(stderr, "%s done: %.1f mm^3 in %.1f s\n", a.materials[i].c_str(),
                     r["volume_mm3"].get<double>(), r["seconds"].get<double>());
      });

  io::Table t;
  t.label_name = "material";
  t.columns = {"volume_mm3",      "mass_mg",          "max_depth_mm",
               "wear_rate_mm3_per_Mc", "mean_peak_pressure_MPa", "peak_pressure_MPa",
               "ap_rom_mm",       "ie_rom_deg",        "elastic_modulus_MPa",
               "wear_factor_mm3_per_Nmm", "friction", "dt_s", "seconds", "contact_area_mm2"};
  // the deformable insert's stress and plastic strain (every material runs the same insert)
  const std::vector<std::string> solid_keys = {
      "von_mises_max_surface_MPa", "von_mises_max_subsurface_MPa", "plastic_strain_max_surface",
      "plastic_strain_max_subsurface"};
  const bool solid = results.front().contains(solid_keys.front());
  if (solid) t.columns.insert(t.columns.end(), solid_keys.begin(), solid_keys.end());
  std::string md = "| material | volume (mm³) | mass (mg) | max depth (mm) | mean peak pressure "
                   "(MPa) | AP ROM (mm) | IE ROM (deg) |";
  md += solid ? " contact area (mm²) | von Mises max surface / subsurface (MPa) | plastic "
                "strain max surface / subsurface |\n|---|---|---|---|---|---|---|---|---|---|\n"
              : "\n|---|---|---|---|---|---|---|\n";
  nlohmann::json all;
  for (size_t i = 0; i < jobs.size(); ++i) {
    const auto& r = results[i];
    const auto& mat = jobs[i].config.material;
    t.label_column.push_back(a.materials[i]);
    std::vector<double> row = {
        r["volume_mm3"], r["mass_mg"], r["max_depth_mm"], r["wear_rate_mm3_per_Mc"],
        r["mean_peak_pressure_MPa"], r["peak_pressure_MPa"], r["ap_rom_mm"], r["ie_rom_deg"],
        mat.elastic_modulus_MPa, mat.wear_factor_mm3_per_Nmm, r["friction"], r["dt_s"],
        r["seconds"], r["contact_area_mm2"]};
    if (solid) {
      for (const std::string& k : solid_keys) row.push_back(r[k].get<double>());
    }
    t.add_row(row);
    char line[256];
    std::snprintf(line, sizeof line, "| %s | %.1f | %.1f | %.3f | %.1f | %.2f | %.2f |",
                  a.materials[i].c_str(), r["volume_mm3"].get<double>(),
                  r["mass_mg"].get<double>(), r["max_depth_mm"].get<double>(),
                  r["mean_peak_pressure_MPa"].get<double>(), r["ap_rom_mm"].get<double>(),
                  r["ie_rom_deg"].get<double>());
    md += line;
    if (solid) {
      std::snprintf(line, sizeof line, " %.1f | %.1f / %.1f | %.4f / %.4f |",
                    r["contact_area_mm2"].get<double>(),
                    r["von_mises_max_surface_MPa"].get<double>(),
                    r["von_mises_max_subsurface_MPa"].get<double>(),
                    r["plastic_strain_max_surface"].get<double>(),
                    r["plastic_strain_max_subsurface"].get<double>());
      md += line;
    }
    md += "\n";
    all[a.materials[i]] = r;
  }
  std::ostringstream head;
  head << "# kneesim compare\n\n" << a.cycles << " cycles, geometry update every "
       << a.update_every << " cycles; same implant, rig and gait for every material.\n\n";
  io::write_csv(fs::path(a.out) / "comparison.csv", t);
  io::write_file_atomic(fs::path(a.out) / "comparison.md", head.str() + md);
  std::vector<std::string> args = {a.out};
  for (const auto& m : a.materials) args.push_back(m);
  if (!a.no_plots) io::run_plot("compare.py", args);
  io::write_json(fs::path(a.out) / "comparison.json", all);
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
      "compare_contact.png) and each material's wear outputs in DIR/<material>/, each "
      "checkpointed at every update (--resume continues a killed comparison). With --set "
      "insert=deformable the table adds the von Mises and plastic-strain maxima.");
  cmd->add_option("config", args->config, "TOML config file")->check(CLI::ExistingFile);
  cmd->add_option("--materials", args->materials, "comma-separated material names")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--cycles", args->cycles, "total gait cycles, 1 to 1e9")
      ->capture_default_str()
      ->check(finite_range(1, 1e9));
  cmd->add_option("--update-every", args->update_every, "cycles per geometry update")
      ->capture_default_str();
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--set", args->sets, "override a config key (repeatable)");
  cmd->add_option("--jobs", args->jobs, "materials simulated at once (default: all cores)")
      ->check(finite_range(1, 1024));
  cmd->add_flag("--no-plots", args->no_plots,
                "skip the PNG plots (the CSV, JSON and Markdown results are the same)");
  cmd->add_flag("--quiet", args->quiet, "no per-material lines or table");
  cmd->add_flag("--resume", args->resume,
                "continue a killed comparison: each material from its DIR/<material>/"
                "wear.checkpoint, a material that had finished from its summary.json");
  cmd->callback([args] {
    io::check_output_folder(args->out);  // before any work
    run(*args);
  });
}

}  // namespace kneesim::cli
