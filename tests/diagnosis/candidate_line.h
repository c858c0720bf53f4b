// One line per candidate of a diagnosis, for the failure reports of the hidden-effect tests
// (block-on-ring and knee): its dAICc and held-out RMSE relative to "none", and its fitted
// parameters.
#pragma once

#include <cstdio>
#include <string>

#include "analysis/diagnosis/diagnose.h"

namespace kneesim::test {

inline std::string candidate_line(const diagnosis::DiagnosisResult& r,
                                  const diagnosis::ModelFit& m) {
  const diagnosis::ModelFit& none = r.candidates.front();
  char buf[200];
  std::snprintf(buf, sizeof buf, "    %s: dAICc %.1f, held-out RMSE / none's %.3f,",
                std::string(diagnosis::effect_name(m.effect)).c_str(), m.aicc - none.aicc,
                m.heldout_rmse / none.heldout_rmse);
  std::string out = buf;
  for (Eigen::Index j = 0; j < m.params.size(); ++j) {
    std::snprintf(buf, sizeof buf, " %s %.4g", m.specs[static_cast<size_t>(j)].name.c_str(),
                  m.params[j]);
    out += buf;
  }
  return out;
}

}  // namespace kneesim::test
