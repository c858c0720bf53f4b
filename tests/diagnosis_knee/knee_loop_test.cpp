// The knee-wear forward model that follows the geometry update (issue 14 item 6), default-suite
// size. References: the wear loop itself (wear::run_wear, an independent integration of the
// same physics: one simulated cycle per update, recession, rebuild) for the forward model, and
// the hidden truth of loop-made data (knee_loop_data.h) for the identification. The long
// version (knee_loop_long.cpp) runs 3 scatter levels x 4 laws x many seeds.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "analysis/diagnosis/knee_wear_case.h"
#include "tests/diagnosis_knee/knee_identification.h"
#include "tests/diagnosis_knee/knee_loop_data.h"

using namespace kneesim;
using diagnosis::Effect;

TEST_CASE("the geometry-following forward model follows the wear loop under a pressure law") {
  // the loop (alpha = 1.49 for this seed, the steep end of the tests' range) on high_load and
  // low_load against the path table's prediction with the same law and k, and the
  // pristine-linear form. Measured (docs/diagnosis.md; `-s` prints each volume): at 3 Mc the
  // path -6.7 % / +1.3 % (high / low load), pristine-linear -32.9 % / -24.0 %; at 1 Mc the path
  // within 4 % and the pristine-linear form within 10 % (the geometry has hardly moved, and
  // which is closer there is not a property of the model). The path's geometry is
  // Archard's at each worn volume, which a steep pressure law (wearing the low-pressure border
  // faster) departs from. Required: within 30 % everywhere, within 10 % at 1 Mc, and closer to
  // the loop than the pristine-linear form at 3 Mc.
  const test::LoopTruth t = test::make_loop_truth(Effect::pressure_dependent_wear, 424242);
  const auto& path = test::knee_test_path_tables();
  const auto& pristine = test::knee_test_tables();
  diagnosis::KneeWearParams p;
  p.effect = Effect::pressure_dependent_wear;
  p.k = t.k;
  p.pressure_exponent = t.params.at("pressure_exponent");
  p.reference_pressure = pristine.at("iso")->mean_pressure();
  for (const std::string c : {"high_load", "low_load"}) {
    CHECK(path.at(c)->geometry_states() == test::kKneePathStates + 1);
    const auto rp = path.at(c)->rates(p);
    const auto r0 = pristine.at(c)->rates(p);
    for (double n : {1e6, 3e6}) {
      const double loop = t.curves.at(c).at(n);
      const double followed = path.at(c)->volume(p, rp, n) * 1e9;
      const double linear = pristine.at(c)->volume(p, r0, n) * 1e9;
      INFO(c << " at " << n << " cycles: loop " << loop << " mm3, path " << followed
             << ", pristine-linear " << linear << " (alpha " << p.pressure_exponent << ")");
      CHECK(std::abs(followed / loop - 1.0) < 0.30);
      if (n < 2e6) {
        CHECK(std::abs(followed / loop - 1.0) < 0.10);
      } else {
        CHECK(std::abs(followed / loop - 1.0) < std::abs(linear / loop - 1.0));
      }
    }
  }
}

TEST_CASE("loop-made knee wear: laws named at 5 % specimen scatter, none at 15 %") {
  // one data set per law (3 specimens per condition, the design the issue found named `none`)
  const auto t = test::run_loop_identification(
      {Effect::none, Effect::pressure_dependent_wear, Effect::cross_shear, Effect::running_in},
      91000, 1, {0.05}, false);
  INFO(t.path[0].failures);
  MESSAGE(t.path[0].gains);
  CHECK(t.path[0].correct == t.path[0].runs);
  CHECK(t.path[0].low_gain == 0);
  const auto clean = test::run_loop_identification({Effect::none}, 92000, 1, {0.15}, false);
  CHECK(clean.path[0].false_positives == 0);
}
