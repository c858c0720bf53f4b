// `kneesim diagnose <case>`: given measured data, show what the baseline model gets wrong,
// name the cause from the effect library, extend the model and measure the gain (issue 4).
// Each case is a sub-command built on the same framework (analysis/diagnosis): it reads its
// measured file, assembles a DiagnosisCase and hands it to diagnose() and write_diagnosis().
// Cases: bor (block-on-ring). The knee-wear and kinematics cases plug in the same way: add an
// add_diagnose_<case>(CLI::App* diagnose) function and one call line below.
#include <cstdio>
#include <memory>

#include "analysis/diagnosis/bor_case.h"
#include "analysis/diagnosis/diagnosis_output.h"
#include "engine/errors.h"
#include "engine/io/output_folder.h"
#include "analysis/report/command_reports.h"
#include "tools/kneesim/bor_options.h"
#include "tools/kneesim/commands.h"
#include "tools/kneesim/diagnose_forces.h"
#include "tools/kneesim/diagnose_knee.h"
#include "tools/kneesim/diagnose_options.h"
#include "tools/kneesim/diagnose_published.h"

namespace kneesim::cli {
namespace {

struct DiagnoseBorOptions {
  std::string measured;
  double calibration_load_N = 225.0;
  double steady_state_from_cycles = 50000.0;
  BorRigOptions rig;
  DiagnoseCommonOptions common;
};

void run_diagnose_bor(const DiagnoseBorOptions& o) {
  if (!(o.calibration_load_N > 0.0 && o.calibration_load_N <= 1e4)) {
    throw InputError("command line: --calibration-load-N = " +
                     std::to_string(o.calibration_load_N) +
                     " N is outside the allowed range (0, 10000] N.");
  }
  if (!(o.steady_state_from_cycles >= 0.0 && o.steady_state_from_cycles <= 1e9)) {
    throw InputError("command line: --steady-state-from-cycles = " +
                     std::to_string(o.steady_state_from_cycles) +
                     " is outside the allowed range [0, 1e9].");
  }
  const diagnosis::DiagnosisOptions options = make_diagnosis_options(o.common);
  diagnosis::BorCaseOptions bo;
  bo.rig = make_bor_rig(o.rig);
  bo.calibration_load = o.calibration_load_N;
  bo.steady_state_from = o.steady_state_from_cycles;
  const auto c = diagnosis::make_bor_case(diagnosis::read_bor_measured(o.measured), bo);
  const auto r = diagnosis::diagnose(c, options);
  std::printf("%s", diagnosis::write_diagnosis(c, r, o.common.out).c_str());
  report::write_diagnosis_report(o.common.out, "bor");
}

void add_diagnose_bor(CLI::App* diagnose) {
  auto opt = std::make_shared<DiagnoseBorOptions>();
  opt->common.out = "kneesim-diagnose-bor";
  CLI::App* cmd = diagnose->add_subcommand(
      "bor", "block-on-ring wear: CSV with load_N, cycles, volume_mm3 [, depth_mm, specimen]");
  cmd->add_option("--measured", opt->measured, "measured CSV file")->required();
  cmd->add_option("--calibration-load-N", opt->calibration_load_N,
                  "load at which k_D is calibrated from the steady-state slope [N]")
      ->capture_default_str()->check(finite_number("(0, 10000] N"));
  cmd->add_option("--steady-state-from-cycles", opt->steady_state_from_cycles,
                  "first cycle count of the steady state used by the calibration")
      ->capture_default_str()->check(finite_number("[0, 1e9]"));
  add_diagnose_common_options(cmd, opt->common);
  add_bor_rig_options(cmd, opt->rig);
  cmd->callback([opt] {
    io::check_output_folder(opt->common.out);  // before any work
    run_diagnose_bor(*opt);
  });
}

}  // namespace

void add_diagnose_command(CLI::App& app) {
  CLI::App* diagnose = app.add_subcommand(
      "diagnose", "Diagnose what the model gets wrong against measured data, name the cause, "
                  "extend the model and measure the gain");
  diagnose->require_subcommand(1);
  add_diagnose_bor(diagnose);
  add_diagnose_knee_wear(diagnose);
  add_diagnose_kinematics(diagnose);
  add_diagnose_forces(diagnose);
  add_diagnose_published_wear(diagnose);
}

}  // namespace kneesim::cli
