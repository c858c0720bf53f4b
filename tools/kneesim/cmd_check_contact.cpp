// `kneesim check-contact [CONFIG]`: the rigid insert's contact law, the one every command uses
// for the config, against the deformable insert under the config's own load case (rig, gait,
// load), with the law as specified beside it (analysis/run/check_contact_law.h). Writes
// DIR/comparison.csv, DIR/summary.json, DIR/calibration.png and DIR/report.html.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "analysis/report/command_reports.h"
#include "analysis/run/check_contact_law.h"
#include "analysis/run/gait_run.h"
#include "engine/io/output_folder.h"
#include "tools/kneesim/commands.h"

namespace kneesim::cli {
namespace {

struct CheckContactArgs {
  std::string config;
  std::string material;
  std::vector<std::string> sets;
  std::string out = "kneesim-check-contact";
  double element_mm = 0.0;
  bool quiet = false;
  bool no_plots = false;
};

void check_contact(const CheckContactArgs& a) {
  // the deformable insert on the calibration's reference mesh unless the config, --element-mm
  // or --set say otherwise
  std::vector<std::string> sets = with_reference_mesh(a.config, a.sets, a.material, a.element_mm);
  run::ContactLawCheckJob job;
  job.config = run::load_run_config(a.config, sets);
  sets.push_back("contact.calibration=\"off\"");
  sets.push_back("contact.law_file=\"\"");
  sets.push_back("contact.foundation_modulus_MPa=0");
  job.specified = run::load_run_config(a.config, sets);
  job.out = a.out;
  job.plots = !a.no_plots;
  job.quiet = a.quiet;
  const nlohmann::json s = run::check_contact_law(job);
  report::write_check_contact_report(a.out, s["material"].get<std::string>());
  const auto& f = s["stance_figures"];
  const auto& e = s["stance_0_60pct"];
  const auto& law = s["contact_law"];
  std::printf("check-contact %s, rig %s: stance 0-60 %% (frames in contact)\n",
              s["material"].get<std::string>().c_str(), s["rig_preset"].get<std::string>().c_str());
  std::printf("  %-28s %9s %9s %9s %9s %11s %11s\n", "", "peak_MPa", "mpeak_MPa", "mean_MPa",
              "area_mm2", "peak_rms_%", "mean_rms_%");
  auto row = [&](const char* label, const char* key, const char* errors) {
    const auto& x = f[key];
    std::printf("  %-28s %9.2f %9.2f %9.2f %9.1f", label, x["peak_MPa"].get<double>(),
                x["mean_peak_MPa"].get<double>(), x["mean_MPa"].get<double>(),
                x["area_mm2"].get<double>());
    if (errors) {
      std::printf(" %11.1f %11.1f\n", 100 * e[errors]["peak_pressure_rms"].get<double>(),
                  100 * e[errors]["mean_pressure_rms"].get<double>());
    } else {
      std::printf("\n");
    }
  };
  row("deformable insert", "deformable", nullptr);
  const std::string law_label = "rigid, law (" + law["source"].get<std::string>() + ")";
  row(law_label.c_str(), "rigid_law", "rigid_law");
  row("rigid, law as specified", "rigid_as_specified", "rigid_as_specified");
  const auto& dl = s["stance_difference"]["rigid_law"];
  std::printf("the law against the deformable insert: peak %+.1f %%, mean of the frame peak "
              "%+.1f %%, mean %+.1f %%, area %+.1f %% -> %s\n",
              100 * dl["peak"].get<double>(), 100 * dl["mean_peak"].get<double>(),
              100 * dl["mean"].get<double>(), 100 * dl["area"].get<double>(),
              (std::filesystem::path(a.out) / "summary.json").c_str());
}

}  // namespace

void add_check_contact_command(CLI::App& app) {
  auto args = std::make_shared<CheckContactArgs>();
  CLI::App* cmd = app.add_subcommand(
      "check-contact",
      "Check the rigid insert's contact law, the one every command uses for the config (the "
      "calibrated law, fitted on the reference load case: the stanmore rig and the shipped "
      "gait), against the deformable insert under the config's own load case (rig preset, "
      "gait, load scale): one deformable gait cycle on the calibration's reference mesh (or the "
      "config's [deformable] keys, --element-mm and --set deformable.*) and the rigid insert with the law and with the law "
      "as specified. Nothing is fitted. Prints the stance (0-60 %) peak, mean and area of the "
      "three runs and the law's frame errors; writes DIR/comparison.csv, DIR/summary.json, "
      "DIR/calibration.png and DIR/report.html. Minutes: the deformable cycle dominates.");
  cmd->add_option("config", args->config, "TOML config file (every key defaulted)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--material", args->material,
                  "material name (library or the config's); default: the config's");
  cmd->add_option("--set", args->sets,
                  "override a config key, e.g. rig.preset=iso or gait.axial_force_scale=1.5 "
                  "(repeatable; insert is set by the check)");
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--element-mm", args->element_mm,
                  "deformable insert element size [mm] (deformable.element_size_mm; default: "
                  "0.5, the calibration's reference)")
      ->check(finite_range(0.2, 10.0));
  cmd->add_flag("--no-plots", args->no_plots, "skip DIR/calibration.png and the runs' plots");
  cmd->add_flag("--quiet", args->quiet, "no progress lines");
  cmd->callback([args] {
    io::check_output_folder(args->out);
    check_contact(*args);
  });
}

}  // namespace kneesim::cli
