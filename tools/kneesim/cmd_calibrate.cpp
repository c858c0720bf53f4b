// `kneesim calibrate-contact [CONFIG]`: fits the rigid insert's effective foundation modulus to
// the deformable insert of the config's implant and material over a gait cycle, under the
// reference load case (analysis/run/calibrate_contact_law.h), and writes DIR/contact_law.toml
// (the shipped laws in models/contact_laws/ are such files: tools/scripts/calibrate_contact_laws.sh
// makes them), DIR/comparison.csv, DIR/summary.json and DIR/calibration.png.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "analysis/report/command_reports.h"
#include "analysis/run/calibrate_contact_law.h"
#include "analysis/run/gait_run.h"
#include "engine/errors.h"
#include "engine/io/output_folder.h"
#include "engine/io/toml_file.h"
#include "models/config.h"
#include "models/contact_law_key.h"
#include "tools/kneesim/commands.h"

namespace kneesim::cli {
namespace {

struct CalibrateArgs {
  std::string config;
  std::string material;
  std::vector<std::string> sets;
  std::string out = "kneesim-calibrate-contact";
  double element_mm = 0.0;
  double exponent = 0.0;
  double reference_edge_mm = 0.0;
  double reference_sdf_mm = 0.0;
  std::string deformable_from;
  bool quiet = false;
  bool no_plots = false;
  std::string command;
};

void calibrate(const CalibrateArgs& a) {
  // the reference mesh: the default [deformable] keys with the laws' reference element size
  // (what a rigid config's law is looked up under), unless the config, --element-mm or --set
  // say otherwise
  std::vector<std::string> sets = with_reference_mesh(a.config, a.sets, a.material, a.element_mm);
  // the calibration starts from the law as specified: no law is looked up for the config
  sets.push_back("contact.calibration=\"off\"");
  run::ContactCalibrationJob job;
  job.config = run::load_run_config(a.config, sets);
  job.config.contact_calibration = "auto";
  // the calibration runs on its reference load case: a --set it would not use is refused, a
  // config's such keys are named (a config for runs may set its rig, gait and solver)
  std::string from_config;
  for (const std::string& key : models::calibration_unused_keys(job.config)) {
    for (const std::string& s : a.sets) {
      if (models::parse_override(s).key != key) continue;
      throw InputError("calibrate-contact: --set " + s + ": the calibration runs on its "
                       "reference load case (the stanmore rig, the shipped gait, the default "
                       "solver and contact settings besides contact.law, the rigid runs on the "
                       "default surfaces), so " + key + " would not be used; set the implant's "
                       "geometry and meshes, material.* and deformable.* keys, or "
                       "--reference-edge-mm and --reference-sdf-mm for the reference's "
                       "surfaces (kneesim check-contact judges the law on another load case).");
    }
    from_config += (from_config.empty() ? "" : ", ") + key;
  }
  if (!from_config.empty() && !a.quiet) {
    std::fprintf(stderr, "calibrate-contact: not used (the calibration runs on its reference "
                 "load case): %s from %s\n", from_config.c_str(),
                 a.config.empty() ? "the defaults" : a.config.c_str());
  }
  job.out = a.out;
  job.deformable_from = a.deformable_from;
  job.command = a.command;
  job.plots = !a.no_plots;
  job.quiet = a.quiet;
  job.exponent = a.exponent;
  job.reference_edge_length_mm = a.reference_edge_mm;
  job.reference_sdf_spacing_mm = a.reference_sdf_mm;
  const run::ContactCalibrationReport r = run::calibrate_contact_law(job);
  report::write_calibrate_report(a.out, r.law.material);
  const auto& held = r.summary["held_out_30_60pct"];
  std::printf("calibrate-contact %s: K %.1f -> %.1f MPa (x%.3f), exponent n %.3f; held-out stance 30-60 %%: "
              "peak %.1f %% -> %.1f %%, mean %.1f %% -> %.1f %% RMS -> %s\n",
              r.law.material.c_str(), r.law.specified_modulus_MPa, r.law.foundation_modulus_MPa,
              r.law.foundation_modulus_MPa / r.law.specified_modulus_MPa, r.law.exponent,
              100 * held["rigid_as_specified"]["peak_pressure_rms"].get<double>(),
              100 * held["rigid_calibrated"]["peak_pressure_rms"].get<double>(),
              100 * held["rigid_as_specified"]["mean_pressure_rms"].get<double>(),
              100 * held["rigid_calibrated"]["mean_pressure_rms"].get<double>(),
              (std::filesystem::path(a.out) / "contact_law.toml").c_str());
}

}  // namespace

std::vector<std::string> with_reference_mesh(const std::string& config,
                                             const std::vector<std::string>& sets,
                                             const std::string& material, double element_mm) {
  const io::TomlDocument file = config.empty() ? io::TomlDocument{} : io::read_toml_file(config);
  std::vector<std::string> out;
  for (const models::ConfigSetting& s : models::kContactCalibrationReferenceMesh) {
    if (!file.count(s.key)) out.push_back(std::string(s.key) + "=" + s.value);
  }
  out.insert(out.end(), sets.begin(), sets.end());
  if (!material.empty()) out.push_back("material.name=\"" + material + "\"");
  if (element_mm > 0.0) out.push_back("deformable.element_size_mm=" + std::to_string(element_mm));
  return out;
}

void add_calibrate_command(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate-contact",
      "Fit the rigid insert's elastic-foundation law p = K_eff g^n (modulus and exponent) to the deformable insert of the "
      "config's implant and material over a gait cycle (Halloran 2005's approach; the "
      "reference load case: the stanmore rig and the shipped gait; the deformable insert: the "
      "footprint-refined mesh of the convergence study: 0.5 mm surface elements where a rigid "
      "cycle finds contact, 6 layers graded 0.15; or the config's [deformable] keys, --element-mm and --set deformable.*). Writes DIR/contact_law.toml (a law file: the commands find "
      "it by its key when it lies in models/contact_laws/ or the cache, or a config names it as "
      "contact.law_file), DIR/comparison.csv, DIR/summary.json (peak and mean pressure and "
      "contact area errors of the law as specified and calibrated, on the fitting window 0-30 % "
      "and held out on 30-60 %; the stance figures; the run-time ratio) and "
      "DIR/calibration.png.");
  cmd->add_option("config", args->config, "TOML config file (every key defaulted)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--material", args->material,
                  "material name (library or the config's); default: the config's");
  cmd->add_option("--set", args->sets,
                  "override an implant geometry or mesh, material.*, deformable.* or "
                  "solver.threads key (repeatable; a key of the load case, e.g. rig.preset or "
                  "gait.*, is refused: the fit runs on the reference load case)");
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--element-mm", args->element_mm,
                  "deformable insert element size [mm] (deformable.element_size_mm; default: "
                  "0.5, the reference of the shipped and cached laws)")
      ->check(finite_range(0.2, 10.0));
  cmd->add_option("--exponent", args->exponent,
                  "fix the law's exponent n of p = K_eff g^n and fit the modulus alone (default: "
                  "n fitted with the modulus, over 0.3 to 1.5)")
      ->check(finite_range(0.2, 2.0));
  cmd->add_option("--reference-edge-mm", args->reference_edge_mm,
                  "triangulate the built-in implant at this edge length [mm] for the deformable "
                  "reference only (default: implant.edge_length_mm, as the rigid runs); stiff "
                  "inserts' small patches need 0.25 to converge")
      ->check(finite_range(0.1, 5.0));
  cmd->add_option("--reference-sdf-mm", args->reference_sdf_mm,
                  "the femur's distance-field spacing [mm] for the deformable reference only "
                  "(default: contact.sdf_spacing_mm, as the rigid runs)")
      ->check(finite_range(0.05, 2.0));
  cmd->add_option("--deformable-from", args->deformable_from,
                  "a finished deformable kneesim run of the same implant, material, rig, "
                  "[deformable] settings and reference surfaces to fit against instead of "
                  "running one");
  cmd->add_flag("--no-plots", args->no_plots, "skip DIR/calibration.png and the runs' plots");
  cmd->add_flag("--quiet", args->quiet, "no progress lines");
  cmd->callback([args] {
    io::check_output_folder(args->out);
    // the command as given, for the law's provenance
    auto number = [](double v) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%g", v);
      return std::string(buf);
    };
    args->command = "kneesim calibrate-contact";
    if (!args->config.empty()) args->command += " " + args->config;
    if (!args->material.empty()) args->command += " --material " + args->material;
    for (const auto& s : args->sets) args->command += " --set " + s;
    if (args->element_mm > 0.0) args->command += " --element-mm " + number(args->element_mm);
    if (args->exponent > 0.0) args->command += " --exponent " + number(args->exponent);
    if (args->reference_edge_mm > 0.0) {
      args->command += " --reference-edge-mm " + number(args->reference_edge_mm);
    }
    if (args->reference_sdf_mm > 0.0) {
      args->command += " --reference-sdf-mm " + number(args->reference_sdf_mm);
    }
    if (!args->deformable_from.empty()) args->command += " --deformable-from " + args->deformable_from;
    calibrate(*args);
  });
}

}  // namespace kneesim::cli
