#include "tools/kneesim/diagnose_options.h"

#include "engine/errors.h"

namespace kneesim::cli {

void add_diagnose_common_options(CLI::App* cmd, DiagnoseCommonOptions& o) {
  cmd->add_option("--out", o.out, "output folder")->capture_default_str();
  cmd->add_option("--bootstrap", o.bootstrap, "bootstrap resamples for the 95 % intervals")
      ->capture_default_str();
  cmd->add_option("--seed", o.seed, "bootstrap seed")->capture_default_str();
  cmd->add_option("--ic-threshold", o.ic_threshold,
                  "AICc drop against 'none' an effect must exceed")->capture_default_str();
  cmd->add_option("--heldout-threshold", o.heldout_threshold,
                  "relative held-out RMSE drop against 'none' an effect must exceed")
      ->capture_default_str();
}

diagnosis::DiagnosisOptions make_diagnosis_options(const DiagnoseCommonOptions& o) {
  auto bad = [](const std::string& s) { throw InputError("command line: " + s); };
  if (o.bootstrap < 0 || o.bootstrap > 100000) {
    bad("--bootstrap = " + std::to_string(o.bootstrap) + " is outside the allowed range [0, 100000].");
  }
  if (!(o.ic_threshold >= 0.0 && o.ic_threshold <= 1000.0)) {
    bad("--ic-threshold = " + std::to_string(o.ic_threshold) + " is outside the allowed range [0, 1000].");
  }
  if (!(o.heldout_threshold >= 0.0 && o.heldout_threshold < 1.0)) {
    bad("--heldout-threshold = " + std::to_string(o.heldout_threshold) +
        " is outside the allowed range [0, 1).");
  }
  diagnosis::DiagnosisOptions d;
  d.bootstrap = o.bootstrap;
  d.seed = o.seed;
  d.ic_threshold = o.ic_threshold;
  d.heldout_threshold = o.heldout_threshold;
  return d;
}

}  // namespace kneesim::cli
