#include "tests/diagnosis_knee/knee_identification.h"

#include <algorithm>
#include <cstdio>

#include "analysis/diagnosis/diagnose.h"
#include "analysis/diagnosis/kinematics_case.h"
#include "analysis/diagnosis/knee_wear_case.h"
#include "tests/diagnosis_knee/knee_hidden_effect.h"

namespace kneesim::test {
namespace {

void tally(KneeTally& t, diagnosis::Effect truth, std::uint64_t seed,
           const diagnosis::DiagnosisResult& r, double min_gain) {
  ++t.runs;
  t.max_seconds = std::max(t.max_seconds, r.seconds);
  t.total_seconds += r.seconds;
  char line[160];
  std::snprintf(line, sizeof line, "%s seed %llu: named %s, gain %.3f, %.2f s\n",
                std::string(diagnosis::effect_name(truth)).c_str(),
                static_cast<unsigned long long>(seed),
                std::string(diagnosis::effect_name(r.effect())).c_str(), r.gain, r.seconds);
  t.gains += line;
  if (r.effect() == truth) {
    ++t.correct;
  } else {
    t.failures += line;
  }
  if (truth == diagnosis::Effect::none && r.effect() != diagnosis::Effect::none) ++t.false_positives;
  if (truth != diagnosis::Effect::none && r.effect() != diagnosis::Effect::none &&
      r.effect() != truth) {
    ++t.wrong_effect;
  }
  if (truth != diagnosis::Effect::none) {
    t.min_gain = std::min(t.min_gain, r.gain);
    if (r.effect() == truth && r.gain < min_gain) ++t.low_gain;
  }
}

}  // namespace

KneeTally run_knee_wear_identification(const std::vector<diagnosis::Effect>& effects,
                                       std::uint64_t first_seed, int seeds, bool with_depth) {
  KneeTally t;
  diagnosis::DiagnosisOptions opt;
  opt.bootstrap = 0;  // identification only
  for (diagnosis::Effect truth : effects) {
    for (int i = 0; i < seeds; ++i) {
      const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(i);
      const KneeSynthetic s = make_synthetic_knee_wear(truth, seed, with_depth);
      const auto c = diagnosis::make_knee_wear_case(s.data, knee_test_tables(), {});
      tally(t, truth, seed, diagnosis::diagnose(c, opt), kKneeWearMinGain);
    }
  }
  return t;
}

KneeTally run_kinematics_identification(const std::vector<diagnosis::Effect>& effects,
                                        std::uint64_t first_seed, int seeds) {
  KneeTally t;
  diagnosis::DiagnosisOptions opt;
  opt.bootstrap = 0;
  opt.multi_start = false;
  for (diagnosis::Effect truth : effects) {
    for (int i = 0; i < seeds; ++i) {
      const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(i);
      const KneeSynthetic s = make_synthetic_kinematics(truth, seed);
      const int sims0 = kinematics_test_simulator()->simulations();
      const auto c = diagnosis::make_kinematics_case(s.data, kinematics_test_simulator(), {});
      tally(t, truth, seed, diagnosis::diagnose(c, opt), kKinematicsMinGain);
      t.gains += "  " + std::to_string(kinematics_test_simulator()->simulations() - sims0) +
                 " simulations\n";
    }
  }
  return t;
}

}  // namespace kneesim::test
