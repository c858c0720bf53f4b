// Outputs of a diagnosis: diagnosis.json (keys of issue 4: baseline {model, params, rmse,
// heldout_rmse}, effect, extended {model, params, params_ci95, rmse, heldout_rmse}, gain,
// candidates [{name, params, heldout_rmse, aicc}]), the readable report diagnosis.md, the
// residual table and the model curves (CSV text; the command writes them atomically).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "analysis/diagnosis/diagnose.h"
#include "analysis/diagnosis/diagnosis_case.h"

namespace kneesim::diagnosis {

nlohmann::json diagnosis_json(const DiagnosisCase& c, const DiagnosisResult& r);

// the technical report: what the baseline gets wrong, the named cause and its physics, the
// extension with its parameters and intervals, the candidates and the gain
std::string diagnosis_markdown(const DiagnosisCase& c, const DiagnosisResult& r);

// one row per measurement: group, specimen, quantity, x, measured, baseline, extended,
// heldout_baseline, heldout_extended
std::string residuals_csv(const DiagnosisCase& c, const DiagnosisResult& r);

// model curves of the baseline and the extension: model, group, quantity, x, value
std::string curves_csv(const DiagnosisCase& c, const DiagnosisResult& r);

}  // namespace kneesim::diagnosis
