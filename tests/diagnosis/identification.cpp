#include "tests/diagnosis/identification.h"

#include <algorithm>

#include "analysis/diagnosis/bor_case.h"
#include "analysis/diagnosis/diagnose.h"
#include "tests/diagnosis/hidden_effect.h"

namespace kneesim::test {

IdentificationTally run_identification(std::uint64_t first_seed, int seeds, bool with_depth) {
  using diagnosis::Effect;
  IdentificationTally t;
  std::vector<Effect> effects = {Effect::none, Effect::running_in,
                                 Effect::pressure_dependent_wear};
  if (with_depth) effects.push_back(Effect::creep);
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
      if (r.effect() == truth) {
        ++t.correct;
      } else {
        t.failures += std::string(diagnosis::effect_name(truth)) + " seed " +
                      std::to_string(seed) + " named " +
                      std::string(diagnosis::effect_name(r.effect())) + "\n";
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
