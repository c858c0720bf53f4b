#include "tools/kneesim/diagnosis_output.h"

#include <cstdio>

#include "analysis/diagnosis/report.h"
#include "engine/errors.h"
#include "tools/io/atomic_file.h"
#include "tools/io/json_out.h"
#include "tools/io/plot.h"

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

void write_diagnosis(const diagnosis::DiagnosisCase& c, const diagnosis::DiagnosisResult& r,
                     const std::filesystem::path& out) {
  io::write_file_atomic(out / "residuals.csv", diagnosis::residuals_csv(c, r));
  io::write_file_atomic(out / "curves.csv", diagnosis::curves_csv(c, r));
  io::write_file_atomic(out / "diagnosis.md", diagnosis::diagnosis_markdown(c, r));
  io::write_json(out / "diagnosis.json", diagnosis::diagnosis_json(c, r));
  const std::string effect(diagnosis::effect_name(r.effect()));
  io::run_plot("diagnosis.py", {(out / "residuals.csv").string(), (out / "curves.csv").string(),
                                (out / "diagnosis.png").string(),
                                c.name + ": effect " + effect});
  std::printf("diagnosis %s: effect %s, held-out RMSE %.4g -> %.4g (%s), gain %.3f, %.2f s -> %s\n",
              c.name.c_str(), effect.c_str(), r.baseline.heldout_rmse, r.extended().heldout_rmse,
              r.rmse_unit.c_str(), r.gain, r.seconds, out.string().c_str());
}

}  // namespace kneesim::cli
