#include "tools/kneesim/diagnose_knee.h"

#include <cstdio>
#include <memory>

#include "analysis/report/command_reports.h"

#include "analysis/diagnosis/knee_diagnosis.h"
#include "engine/io/output_folder.h"
#include "tools/kneesim/commands.h"
#include "tools/kneesim/diagnose_options.h"

namespace kneesim::cli {
namespace {

struct DiagnoseKneeWearOptions {
  diagnosis::KneeWearDiagnosisOptions run;
  DiagnoseCommonOptions common;
  bool no_calibrate = false;     // the rigid contact law as specified
};

void run_diagnose_knee_wear(const DiagnoseKneeWearOptions& o) {
  diagnosis::KneeWearDiagnosisOptions ro = o.run;
  ro.options = make_diagnosis_options(o.common);
  ro.out = o.common.out;
  const diagnosis::KneeWearDiagnosisReport r = diagnosis::run_knee_wear_diagnosis(ro);
  std::printf("%s", r.summary_line.c_str());
  report::write_diagnosis_report(o.common.out, "knee-wear");
  std::printf("knee-wear: %zu conditions simulated in %.1f s, total %.1f s\n", r.conditions,
              r.sim_seconds, r.total_seconds);
  if (!r.check.is_null() && r.check["status"] == "complete") {
    std::printf("approximation check: linear vs wear loop volume %+.1f %%, max depth %+.1f %%\n",
                r.check["volume_difference_pct"].get<double>(),
                r.check["max_depth_difference_pct"].get<double>());
  }
}

struct DiagnoseKinematicsOptions {
  diagnosis::KinematicsDiagnosisOptions run;
  bool multi_start = false;      // multi-start the full-data fits
  DiagnoseCommonOptions common;
  bool no_calibrate = false;     // the rigid contact law as specified
};

void run_diagnose_kinematics(const DiagnoseKinematicsOptions& o) {
  diagnosis::KinematicsDiagnosisOptions ro = o.run;
  ro.options = make_diagnosis_options(o.common);
  ro.options.multi_start = o.multi_start;
  ro.out = o.common.out;
  const diagnosis::KinematicsDiagnosisReport r = diagnosis::run_kinematics_diagnosis(ro);
  std::printf("%s", r.summary_line.c_str());
  report::write_diagnosis_report(o.common.out, "kinematics");
  std::printf("kinematics: %d simulations in %.1f s, total %.1f s\n", r.simulations,
              r.sim_seconds, r.total_seconds);
}

}  // namespace

void add_diagnose_knee_wear(CLI::App* diagnose) {
  auto opt = std::make_shared<DiagnoseKneeWearOptions>();
  opt->common.out = "kneesim-diagnose-knee-wear";
  CLI::App* cmd = diagnose->add_subcommand(
      "knee-wear", "knee simulator wear: CSV with condition, cycles, volume_mm3 [, max_depth_mm, "
                   "specimen]; conditions are [conditions.<name>] of the config");
  cmd->add_option("--measured", opt->run.measured, "measured CSV file")->required();
  cmd->add_option("--config", opt->run.config, "TOML config with the [conditions.<name>] tables")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--set", opt->run.sets, "override a config key for every condition (repeatable)");
  cmd->add_option("--calibration-condition", opt->run.calibration_condition,
                  "condition whose steady-state slope calibrates k (default: the first in the "
                  "file)");
  cmd->add_option("--steady-state-from-cycles", opt->run.steady_state_from_cycles,
                  "first cycle count of the steady state used by the calibration")
      ->capture_default_str()->check(finite_number("[0, 1e9]"));
  cmd->add_option("--check-updates", opt->run.check_updates,
                  "geometry updates of the full wear-loop check of the linear approximation "
                  "(0: no check)")
      ->capture_default_str()->check(whole_range(0, 100));
  cmd->add_option("--geometry-states", opt->run.geometry_states,
                  "worn geometry states the forward model follows along each condition's wear "
                  "loop (0: wear linear in cycles on the pristine insert)")
      ->capture_default_str()->check(whole_range(0, 50));
  add_diagnose_common_options(cmd, opt->common);
  add_no_calibrate_flag(cmd, opt->no_calibrate);
  cmd->callback([opt] {
    io::check_output_folder(opt->common.out);  // before any work
    prepare_contact_law(opt->run.config, opt->run.sets, opt->no_calibrate);
    run_diagnose_knee_wear(*opt);
  });
}

void add_diagnose_kinematics(CLI::App* diagnose) {
  auto opt = std::make_shared<DiagnoseKinematicsOptions>();
  opt->common.out = "kneesim-diagnose-kinematics";
  opt->common.bootstrap = 10;  // every resample refits full simulations
  CLI::App* cmd = diagnose->add_subcommand(
      "kinematics", "tibiofemoral kinematics: CSV with gait_pct, ap_mm, ie_deg, or the DM "
                    "fluoroscopy .sto, against the force-controlled rig of the config");
  cmd->add_option("--measured", opt->run.measured, "measured CSV or .sto file")->required();
  cmd->add_option("--config", opt->run.config, "TOML config of the rig and implant")->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--set", opt->run.sets, "override a config key (repeatable)");
  cmd->add_option("--stance-end-pct", opt->run.stance_end_pct,
                  "gait % that ends stance in the phase split")
      ->capture_default_str()->check(finite_number("(0, 100) %"));
  cmd->add_flag("--multi-start", opt->multi_start,
                "multi-start the full-data fits (about three times the simulations)");
  cmd->add_option("--threads", opt->run.threads,
                  "rig simulations run at a time (results do not depend on it)")
      ->capture_default_str()->check(whole_range(1, 256));
  add_diagnose_common_options(cmd, opt->common);
  add_no_calibrate_flag(cmd, opt->no_calibrate);
  cmd->callback([opt] {
    io::check_output_folder(opt->common.out);  // before any work
    prepare_contact_law(opt->run.config, opt->run.sets, opt->no_calibrate);
    run_diagnose_kinematics(*opt);
  });
}

}  // namespace kneesim::cli
