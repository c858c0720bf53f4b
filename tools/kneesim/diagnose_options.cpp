#include "tools/kneesim/diagnose_options.h"

#include <cmath>
#include <cstdlib>

#include <cstdio>

#include "analysis/run/calibrate_contact_law.h"
#include "analysis/run/gait_run.h"
#include "engine/errors.h"
#include "tools/kneesim/commands.h"

namespace kneesim::cli {

void add_diagnose_common_options(CLI::App* cmd, DiagnoseCommonOptions& o) {
  cmd->add_option("--out", o.out, "output folder")->capture_default_str();
  cmd->add_option("--bootstrap", o.bootstrap, "bootstrap resamples for the 95 % intervals")
      ->capture_default_str()->check(whole_range(0, 100000));
  cmd->add_option("--seed", o.seed, "seed of the bootstrap and of the detection-limit replicates")
      ->capture_default_str()->check(whole_range(0, kMaxSeed));
  cmd->add_option("--ic-threshold", o.ic_threshold,
                  "AICc drop against 'none' an effect must exceed")
      ->capture_default_str()->check(finite_number("[0, 1000]"));
  cmd->add_option("--heldout-threshold", o.heldout_threshold,
                  "relative held-out RMSE drop against 'none' an effect must exceed")
      ->capture_default_str()->check(finite_number("[0, 1)"));
  cmd->add_option("--noise-model", o.noise_model,
                  "error model of the fits: white (independent residuals), correlated "
                  "(residuals correlated along each series; specimen offsets), instrument "
                  "(correlated plus the instrument's nuisance terms)")
      ->capture_default_str();
  cmd->add_option("--noise-param", o.noise_params,
                  "key=value of the error model (repeatable; the case's report lists its keys, "
                  "e.g. gain_crosstalk_sd=0.01 for forces, ou=1 to correlate wear residuals)");
  cmd->add_option("--detection-replicates", o.detection_replicates,
                  "simulated data sets per detection limit (0: no detection limits)")
      ->capture_default_str()->check(whole_range(0, 10000));
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
  if (o.detection_replicates < 0 || o.detection_replicates > 10000) {
    bad("--detection-replicates = " + std::to_string(o.detection_replicates) +
        " is outside the allowed range [0, 10000].");
  }
  diagnosis::DiagnosisOptions d;
  d.noise_model = o.noise_model;
  for (const std::string& kv : o.noise_params) {
    const auto eq = kv.find('=');
    char* end = nullptr;
    const double v = eq == std::string::npos ? 0.0 : std::strtod(kv.c_str() + eq + 1, &end);
    if (eq == std::string::npos || eq == 0 || end == kv.c_str() + eq + 1 || *end != '\0' ||
        !std::isfinite(v)) {
      bad("--noise-param '" + kv + "' is not key=value with a number value.");
    }
    d.noise_params[kv.substr(0, eq)] = v;
  }
  d.detection_replicates = o.detection_replicates;
  d.bootstrap = o.bootstrap;
  d.seed = o.seed;
  d.ic_threshold = o.ic_threshold;
  d.heldout_threshold = o.heldout_threshold;
  return d;
}

void prepare_contact_law(const std::string& config, std::vector<std::string>& sets,
                         bool no_calibrate) {
  sets = with_no_calibrate(sets, no_calibrate);
  // the law is resolved here for its warning; a calibration on first use runs in the diagnosis,
  // once the measured data are read
  const models::Config c = run::load_run_config(config, sets);
  if (const std::string& w = c.contact_law_resolution.warning; !w.empty()) {
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
}

}  // namespace kneesim::cli
