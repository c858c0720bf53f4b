#include "tests/diagnosis/identification.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "analysis/diagnosis/bor_case.h"
#include "analysis/diagnosis/diagnose.h"
#include "tests/diagnosis/candidate_line.h"
#include "tests/diagnosis/hidden_effect.h"

namespace kneesim::test {

std::vector<diagnosis::Effect> bor_test_effects(bool with_depth) {
  using diagnosis::Effect;
  std::vector<Effect> effects = {Effect::none, Effect::running_in, Effect::incubation,
                                 Effect::pressure_dependent_wear};
  if (with_depth) effects.push_back(Effect::creep);
  return effects;
}

IdentificationTally run_identification(std::uint64_t first_seed, int seeds, bool with_depth,
                                       const std::vector<diagnosis::Effect>& effects) {
  using diagnosis::Effect;
  IdentificationTally t;
  diagnosis::DiagnosisOptions opt;
  opt.bootstrap = 0;  // identification only; the bootstrap is tested on its own
  for (Effect truth : effects) {
    for (int i = 0; i < seeds; ++i) {
      SyntheticOptions so;
      so.with_depth = with_depth;
      const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(i);
      const SyntheticData s = make_synthetic_bor(truth, seed, so);
      const auto c = diagnosis::make_bor_case(s.data, diagnosis::BorCaseOptions{});
      const auto r = diagnosis::diagnose(c, opt);
      ++t.runs;
      t.max_seconds = std::max(t.max_seconds, r.seconds);
      t.total_seconds += r.seconds;
      const double aicc_none = r.candidates.front().aicc;
      const double heldout_none = r.candidates.front().heldout_rmse;
      for (const auto& m : r.candidates) {
        if (m.effect == Effect::none) continue;
        const double ratio = m.heldout_rmse / heldout_none;
        if (truth == Effect::none) {
          t.clean_min_daicc = std::min(t.clean_min_daicc, m.aicc - aicc_none);
          t.clean_min_heldout_ratio = std::min(t.clean_min_heldout_ratio, ratio);
        }
        if (m.effect == truth) {
          t.effect_max_daicc = std::max(t.effect_max_daicc, m.aicc - aicc_none);
          t.effect_max_heldout_ratio = std::max(t.effect_max_heldout_ratio, ratio);
        }
      }
      if (r.effect() == truth) {
        ++t.correct;
      } else {
        char line[200];
        std::snprintf(line, sizeof line, "%s seed %llu named %s (dAICc %.1f, held-out ratio %.3f)\n",
                      std::string(diagnosis::effect_name(truth)).c_str(),
                      static_cast<unsigned long long>(seed),
                      std::string(diagnosis::effect_name(r.effect())).c_str(),
                      r.extended().aicc - aicc_none,
                      r.extended().heldout_rmse / r.candidates.front().heldout_rmse);
        t.failures += line;
        for (const auto& m : r.candidates) {
          t.failures += candidate_line(r, m);
          for (size_t q = 0; q < r.quantities.size(); ++q) {
            double ss = 0.0, ssh = 0.0;
            int n = 0;
            for (size_t i = 0; i < s.data.rows.size(); ++i) {
              if (s.data.rows[i].quantity != r.quantities[q]) continue;
              const auto k = static_cast<Eigen::Index>(i);
              ss += std::pow(m.predictions[k] - s.data.rows[i].value, 2);
              ssh += std::pow(m.heldout_predictions[k] - s.data.rows[i].value, 2);
              ++n;
            }
            std::snprintf(line, sizeof line, " rmse(%s) %.3g heldout %.3g", r.quantities[q].c_str(),
                          std::sqrt(ss / n), std::sqrt(ssh / n));
            t.failures += line;
          }
          for (size_t q = 0; q < m.noise_sd.size(); ++q) {
            std::snprintf(line, sizeof line, " sd(%s) %.3g", r.quantities[q].c_str(), m.noise_sd[q]);
            t.failures += line;
          }
          t.failures += "\n";
        }
      }
      if (truth == Effect::none && r.effect() != Effect::none) ++t.false_positives;
      if (truth != Effect::none) {
        t.min_gain = std::min(t.min_gain, r.gain);
        if (r.effect() == truth && r.gain < kMinGain) ++t.low_gain;
      }
    }
  }
  return t;
}

}  // namespace kneesim::test
