// `kneesim calibrate-contact [CONFIG] --material NAME`: runs the deformable insert over a gait
// cycle, fits the rigid path's effective foundation modulus to its stance peak and mean
// pressure (analysis/run/contact_calibration.h; models/contact_law_file.h says why one
// modulus), and writes DIR/contact_law.toml (a config names it as contact.law_file),
// DIR/comparison.csv (the three traces per frame), DIR/summary.json and DIR/calibration.png.
// The fit uses the first half of stance (0-30 % of the cycle); the second half (30-60 %) is
// the held-out judgement. The runs are kept in DIR/deformable, DIR/rigid (as specified) and
// DIR/rigid_calibrated.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "analysis/run/contact_calibration.h"
#include "analysis/run/gait_run.h"
#include "engine/contact_law.h"
#include "engine/errors.h"
#include "engine/io/atomic_file.h"
#include "engine/io/json_out.h"
#include "engine/io/output_folder.h"
#include "engine/io/plot.h"
#include "engine/io/table.h"
#include "models/contact_law_file.h"
#include "analysis/report/command_reports.h"
#include "tools/kneesim/commands.h"

namespace kneesim::cli {
namespace {

struct CalibrateArgs {
  std::string config;
  std::string material;
  std::vector<std::string> sets;
  std::string out = "kneesim-calibrate-contact";
  double element_mm = 2.0;
  std::string deformable_from;
};

constexpr double kFitLo = 0.0, kFitHi = 30.0, kHeldLo = 30.0, kHeldHi = 60.0;

nlohmann::json errors_json(const run::TraceErrors& e) {
  return {{"peak_pressure_rms", e.peak}, {"mean_pressure_rms", e.mean},
          {"contact_area_rms", e.area}, {"frames", e.frames}};
}

void calibrate(const CalibrateArgs& a) {
  namespace fs = std::filesystem;
  const fs::path out = a.out;
  std::vector<std::string> sets = a.sets;
  sets.push_back("material.name=\"" + a.material + "\"");
  models::Config base = run::load_run_config(a.config, sets);
  if (!base.contact_law_file.empty()) {
    throw InputError("command line: the config names contact.law_file = " +
                     base.contact_law_file + "; calibrate from the law as specified (remove it).");
  }
  base.insert_kind = "rigid";
  base.contact_foundation_modulus_MPa = 0.0;
  const std::string implant = models::implant_identity(base);
  const double k_spec_MPa =
      engine::foundation_modulus(base.material.elastic_modulus_MPa, base.material.poisson);

  // the deformable insert over one cycle (or a run given with --deformable-from)
  double deformable_seconds = 0.0;
  fs::path deformable_csv;
  if (a.deformable_from.empty()) {
    run::GaitRunJob job;
    job.config = base;
    job.config.insert_kind = "deformable";
    job.config.deformable_element_size_mm = a.element_mm;
    job.config.cycles = 1;
    job.out = out / "deformable";
    std::fprintf(stderr, "calibrate-contact: deformable insert, %g mm elements, 1 cycle\n",
                 a.element_mm);
    deformable_seconds = run::run_gait_job(job).seconds;
    deformable_csv = job.out / "kinematics.csv";
  } else {
    deformable_csv = fs::path(a.deformable_from) / "kinematics.csv";
    const auto summary = nlohmann::json::parse(io::read_file(fs::path(a.deformable_from) / "summary.json"));
    if (summary.value("insert", std::string()) != "deformable" ||
        summary.value("material", std::string()) != a.material) {
      throw InputError(a.deformable_from + "/summary.json: --deformable-from must name a "
                       "finished deformable run of material " + a.material + ".");
    }
    deformable_seconds = summary.value("seconds_per_cycle", 0.0);
  }
  const run::PressureTrace deformable = run::read_pressure_trace(deformable_csv);

  // a rigid run at a foundation modulus (0: the material's), its trace and seconds per cycle
  auto rigid_run = [&](double modulus_MPa, const fs::path& dir, double* seconds) {
    run::GaitRunJob job;
    job.config = base;
    job.config.contact_foundation_modulus_MPa = modulus_MPa;
    job.out = dir;
    job.quiet = true;
    const run::GaitRunReport r = run::run_gait_job(job);
    if (seconds) *seconds = r.seconds / job.config.cycles;
    return run::read_pressure_trace(dir / "kinematics.csv");
  };
  double rigid_seconds = 0.0;
  const run::PressureTrace specified = rigid_run(0.0, out / "rigid", &rigid_seconds);

  int evaluations = 0;
  const double lo = 0.02 * k_spec_MPa, hi = 2.0 * k_spec_MPa;
  const double k_fit = run::minimize_log_golden(
      [&](double k) {
        const auto t = rigid_run(k, out / "fit", nullptr);
        const auto e = run::compare_traces(t, deformable, kFitLo, kFitHi);
        std::fprintf(stderr, "calibrate-contact: K %.1f MPa: peak %.3f, mean %.3f (RMS, 0-30 %%)\n",
                     k, e.peak, e.mean);
        return e.peak * e.peak + e.mean * e.mean;
      },
      lo, hi, 0.01, evaluations);
  fs::remove_all(out / "fit");
  const bool at_bound = k_fit < 1.05 * lo || k_fit > hi / 1.05;
  double calibrated_seconds = 0.0;
  const run::PressureTrace calibrated = rigid_run(k_fit, out / "rigid_calibrated", &calibrated_seconds);

  models::CalibratedContactLaw law;
  law.material = a.material;
  law.implant = implant;
  law.law = base.contact_law;
  law.foundation_modulus_MPa = k_fit;
  law.specified_modulus_MPa = k_spec_MPa;
  law.fitted_on = "stance 0-30 % peak and mean pressure of the deformable insert (" +
                  std::to_string(a.element_mm).substr(0, 4) + " mm elements), rig " +
                  base.rig_preset;
  models::write_contact_law_file(out / "contact_law.toml", law);

  io::Table t;
  t.columns = {"gait_pct", "deformable_peak_MPa", "deformable_mean_MPa", "deformable_area_mm2",
               "rigid_peak_MPa", "rigid_mean_MPa", "rigid_area_mm2", "calibrated_peak_MPa",
               "calibrated_mean_MPa", "calibrated_area_mm2"};
  for (size_t i = 0; i < deformable.gait_pct.size(); ++i) {
    t.add_row({deformable.gait_pct[i], deformable.peak_MPa[i], deformable.mean_MPa[i],
               deformable.area_mm2[i], specified.peak_MPa[i], specified.mean_MPa[i],
               specified.area_mm2[i], calibrated.peak_MPa[i], calibrated.mean_MPa[i],
               calibrated.area_mm2[i]});
  }
  io::write_csv(out / "comparison.csv", t);

  nlohmann::json s;
  s["material"] = a.material;
  s["implant"] = implant;
  s["law"] = base.contact_law;
  s["specified_modulus_MPa"] = k_spec_MPa;
  s["calibrated_modulus_MPa"] = k_fit;
  s["modulus_ratio"] = k_fit / k_spec_MPa;
  s["search_range_MPa"] = {lo, hi};
  s["fit_at_search_bound"] = at_bound;
  s["fit_evaluations"] = evaluations;
  s["deformable_element_mm"] = a.element_mm;
  for (const auto& [name, lo_pct, hi_pct] :
       {std::tuple{"fit_window_0_30pct", kFitLo, kFitHi},
        std::tuple{"held_out_30_60pct", kHeldLo, kHeldHi},
        std::tuple{"stance_0_60pct", kFitLo, kHeldHi}}) {
    s[name]["rigid_as_specified"] = errors_json(run::compare_traces(specified, deformable, lo_pct, hi_pct));
    s[name]["rigid_calibrated"] = errors_json(run::compare_traces(calibrated, deformable, lo_pct, hi_pct));
  }
  s["seconds_per_cycle"] = {{"deformable", deformable_seconds},
                            {"rigid_as_specified", rigid_seconds},
                            {"rigid_calibrated", calibrated_seconds}};
  s["rigid_over_deformable_time"] = deformable_seconds > 0 ? rigid_seconds / deformable_seconds : 0.0;
  io::write_json(out / "summary.json", s);
  report::write_calibrate_report(out, a.material);
  io::run_plot("calibrate.py", {(out / "comparison.csv").string(),
                                (out / "calibration.png").string(), a.material});
  const auto held = run::compare_traces(calibrated, deformable, kHeldLo, kHeldHi);
  const auto held_spec = run::compare_traces(specified, deformable, kHeldLo, kHeldHi);
  std::printf("calibrate-contact %s: K %.1f -> %.1f MPa (x%.3f)%s; held-out stance 30-60 %%: "
              "peak %.1f %% -> %.1f %%, mean %.1f %% -> %.1f %% RMS -> %s\n",
              a.material.c_str(), k_spec_MPa, k_fit, k_fit / k_spec_MPa,
              at_bound ? " AT A SEARCH BOUND" : "", 100 * held_spec.peak, 100 * held.peak,
              100 * held_spec.mean, 100 * held.mean, (out / "contact_law.toml").c_str());
}

}  // namespace

void add_calibrate_command(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate-contact",
      "Fit the rigid insert's elastic-foundation modulus to the deformable insert over a gait "
      "cycle (Halloran 2005's approach; docs/deformable.md). Writes DIR/contact_law.toml (name "
      "it in a config as contact.law_file), DIR/comparison.csv, DIR/summary.json (peak and "
      "mean pressure and contact area errors of the rigid law as specified and calibrated, on "
      "the fitting window 0-30 % and held out on 30-60 %, and the run-time ratio) and "
      "DIR/calibration.png.");
  cmd->add_option("config", args->config, "TOML config file (every key defaulted)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--material", args->material, "material name (library or the config's)")
      ->required();
  cmd->add_option("--set", args->sets, "override a config key (repeatable)");
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--element-mm", args->element_mm, "deformable insert element size [mm]")
      ->capture_default_str()->check(finite_range(0.5, 5.0));
  cmd->add_option("--deformable-from", args->deformable_from,
                  "a finished deformable kneesim run of the same config and material to fit "
                  "against instead of running one");
  cmd->callback([args] {
    io::check_output_folder(args->out);
    calibrate(*args);
  });
}

}  // namespace kneesim::cli
