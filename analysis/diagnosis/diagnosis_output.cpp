#include "analysis/diagnosis/diagnosis_output.h"

#include <cstdio>

#include "analysis/diagnosis/report.h"
#include "engine/io/atomic_file.h"
#include "engine/io/json_out.h"
#include "engine/io/plot.h"

namespace kneesim::diagnosis {

std::string write_diagnosis(const DiagnosisCase& c, const DiagnosisResult& r,
                            const std::filesystem::path& out) {
  io::write_file_atomic(out / "residuals.csv", residuals_csv(c, r));
  io::write_file_atomic(out / "curves.csv", curves_csv(c, r));
  io::write_file_atomic(out / "diagnosis.md", diagnosis_markdown(c, r));
  io::write_json(out / "diagnosis.json", diagnosis_json(c, r));
  const std::string effect(effect_name(r.effect()));
  io::run_plot("diagnosis.py", {(out / "residuals.csv").string(), (out / "curves.csv").string(),
                                (out / "diagnosis.png").string(),
                                c.name + ": effect " + effect});
  char line[512];
  std::snprintf(line, sizeof line,
                "diagnosis %s: effect %s, held-out RMSE %.4g -> %.4g (%s), gain %.3f "
                "(against the trivial predictor %.4g: %.3f), %.2f s -> %s\n",
                c.name.c_str(), effect.c_str(), r.baseline.heldout_rmse,
                r.extended().heldout_rmse, r.rmse_unit.c_str(), r.gain,
                r.trivial.heldout_rmse, r.gain_vs_trivial, r.seconds, out.string().c_str());
  std::string console = line;
  if (r.tied_with >= 0) {
    const ModelFit& t = r.candidates[static_cast<size_t>(r.tied_with)];
    std::snprintf(line, sizeof line,
                  "  %s fits as well (AICc %+.1f against the named one's, within %g: the data's "
                  "likelihood does not tell them apart); named by the lower held-out RMSE (%.4g "
                  "against %.4g)\n",
                  std::string(effect_name(t.effect)).c_str(), t.aicc - r.extended().aicc,
                  r.tie_band, r.extended().heldout_rmse, t.heldout_rmse);
    console += line;
  }
  return console;
}

void append_report(const std::filesystem::path& out, const std::string& section) {
  const std::filesystem::path md = out / "diagnosis.md";
  io::write_file_atomic(md, io::read_file(md) + "\n" + section);
}

}  // namespace kneesim::diagnosis
