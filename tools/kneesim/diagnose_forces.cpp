#include "engine/io/source_tree.h"
#include "tools/kneesim/diagnose_forces.h"

#include <cstdio>
#include <memory>

#include "analysis/report/command_reports.h"

#include "analysis/diagnosis/forces_diagnosis.h"
#include "engine/io/output_folder.h"
#include "tools/kneesim/commands.h"
#include "tools/kneesim/diagnose_options.h"

namespace kneesim::cli {
namespace {

struct DiagnoseForcesOptions {
  diagnosis::ForcesDiagnosisOptions run;
  DiagnoseCommonOptions common;
  bool no_calibrate = false;     // the rigid contact law as specified
};

void run_diagnose_forces(DiagnoseForcesOptions o) {
  o.run.options = make_diagnosis_options(o.common);
  o.run.out = o.common.out;
  const diagnosis::ForcesDiagnosisReport r = diagnosis::run_forces_diagnosis(o.run);
  std::printf("%s", r.summary_line.c_str());
  report::write_diagnosis_report(o.common.out, "forces");
  std::printf("forces: %d simulations in %.1f s, total %.1f s\n", r.simulations, r.sim_seconds,
              r.total_seconds);
}

}  // namespace

void add_diagnose_forces(CLI::App* diagnose) {
  auto opt = std::make_shared<DiagnoseForcesOptions>();
  opt->common.out = "kneesim-diagnose-forces";
  opt->run.config = (kneesim::io::source_dir() / "models/examples/jw_measured_loads.toml").string();
  CLI::App* cmd = diagnose->add_subcommand(
      "forces", "medial and lateral compartment forces of an instrumented knee (e.g. the Grand "
                "Challenge JW tray) against the rig driven by the same measured loads; the "
                "config's [gait.measured] names the columns, units and the cycle window");
  cmd->add_option("--measured", opt->run.measured,
                  "measured table (default: the config's gait.measured.file)");
  cmd->add_option("--config", opt->run.config,
                  "TOML config of the rig, implant and [gait.measured] columns")
      ->capture_default_str()
      ->check(CLI::ExistingFile);
  cmd->add_option("--set", opt->run.sets, "override a config key (repeatable)");
  cmd->add_option("--grid-points", opt->run.case_options.grid_points,
                  "full simulations per candidate and cycle across its parameter bounds")
      ->capture_default_str()->check(whole_range(4, 41));
  cmd->add_option("--threads", opt->run.threads, "simulations run at a time")
      ->capture_default_str()->check(whole_range(1, 256));
  add_diagnose_common_options(cmd, opt->common);
  add_no_calibrate_flag(cmd, opt->no_calibrate);
  cmd->callback([opt] {
    io::check_output_folder(opt->common.out);  // before any work
    prepare_contact_law(opt->run.config, opt->run.sets, opt->no_calibrate);
    run_diagnose_forces(*opt);
  });
}

}  // namespace kneesim::cli
