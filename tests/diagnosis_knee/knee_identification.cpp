#include "tests/diagnosis_knee/knee_identification.h"

#include <algorithm>
#include <cstdio>

#include "analysis/diagnosis/diagnose.h"
#include "analysis/diagnosis/kinematics_case.h"
#include "analysis/diagnosis/knee_wear_case.h"
#include "tests/diagnosis/candidate_line.h"
#include "tests/diagnosis_knee/knee_hidden_effect.h"
#include "tests/diagnosis_knee/knee_loop_data.h"

namespace kneesim::test {
namespace {

void tally(IdentificationTally& t, diagnosis::Effect truth, std::uint64_t seed,
           const diagnosis::DiagnosisResult& r, double min_gain) {
  ++t.runs;
  t.max_seconds = std::max(t.max_seconds, r.seconds);
  t.total_seconds += r.seconds;
  const double aicc_none = r.candidates.front().aicc;
  double truth_daicc = 0.0;
  for (const auto& m : r.candidates) {
    if (m.effect == diagnosis::Effect::none) continue;
    const double ratio = m.heldout_rmse / r.candidates.front().heldout_rmse;
    if (truth == diagnosis::Effect::none) {
      t.clean_min_daicc = std::min(t.clean_min_daicc, m.aicc - aicc_none);
      t.clean_min_heldout_ratio = std::min(t.clean_min_heldout_ratio, ratio);
    }
    if (m.effect == truth) {
      truth_daicc = m.aicc - aicc_none;
      t.effect_max_daicc = std::max(t.effect_max_daicc, truth_daicc);
      t.effect_max_heldout_ratio = std::max(t.effect_max_heldout_ratio, ratio);
    }
  }
  char line[200];
  std::snprintf(line, sizeof line, "%s seed %llu: named %s, gain %.3f, dAICc of the truth %.1f, "
                "%.2f s\n", std::string(diagnosis::effect_name(truth)).c_str(),
                static_cast<unsigned long long>(seed),
                std::string(diagnosis::effect_name(r.effect())).c_str(), r.gain, truth_daicc,
                r.seconds);
  t.gains += line;
  if (r.effect() == truth) {
    ++t.correct;
  } else {
    t.failures += line;
    for (const auto& m : r.candidates) {
      t.failures += candidate_line(r, m) + "\n";
    }
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

IdentificationTally run_knee_wear_identification(const std::vector<diagnosis::Effect>& effects,
                                       std::uint64_t first_seed, int seeds, bool with_depth,
                                       int specimens) {
  IdentificationTally t;
  diagnosis::DiagnosisOptions opt;
  opt.bootstrap = 0;  // identification only
  for (diagnosis::Effect truth : effects) {
    for (int i = 0; i < seeds; ++i) {
      const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(i);
      const KneeSynthetic s = make_synthetic_knee_wear(truth, seed, with_depth,
                                                        specimens > 0 ? specimens : kKneeSpecimens);
      const auto c = diagnosis::make_knee_wear_case(s.data, knee_test_tables(), {});
      tally(t, truth, seed, diagnosis::diagnose(c, opt), kKneeWearMinGain);
    }
  }
  return t;
}

LoopTallies run_loop_identification(const std::vector<diagnosis::Effect>& effects,
                                    std::uint64_t first_seed, int seeds,
                                    const std::vector<double>& cvs, bool linear_too,
                                    int specimens) {
  LoopTallies t;
  t.path.resize(cvs.size());
  t.linear.resize(cvs.size());
  diagnosis::DiagnosisOptions opt;
  opt.bootstrap = 0;
  for (diagnosis::Effect truth : effects) {
    for (int i = 0; i < seeds; ++i) {
      const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(i);
      const LoopTruth lt = make_loop_truth(truth, seed);
      for (size_t j = 0; j < cvs.size(); ++j) {
        const KneeSynthetic s = make_loop_knee_wear(lt, seed * 7 + j, cvs[j], specimens);
        const auto c = diagnosis::make_knee_wear_case(s.data, knee_test_path_tables(), {});
        tally(t.path[j], truth, seed, diagnosis::diagnose(c, opt), kKneeWearMinGain);
        if (linear_too) {
          const auto l = diagnosis::make_knee_wear_case(s.data, knee_test_tables(), {});
          tally(t.linear[j], truth, seed, diagnosis::diagnose(l, opt), kKneeWearMinGain);
        }
      }
    }
  }
  return t;
}

IdentificationTally run_kinematics_identification(const std::vector<diagnosis::Effect>& effects,
                                        std::uint64_t first_seed, int seeds) {
  IdentificationTally t;
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
