// Long hidden-effect runs of the knee cases (label "long"): 20 seeds per knee-wear effect with
// depth, 10 without, and 5 per kinematic effect; same requirements as the default suite,
// except for volume-only data, where a pressure effect shows only through the one
// high-load condition (26 % higher mean pressure, 3 specimens): there the measured rate is
// 38 of 40 data sets (the two misses, alpha near the low end, were named "none", never a wrong
// effect), so the test requires no wrong effect, no false positive and at least 90 %.
#include <doctest/doctest.h>

#include "tests/diagnosis_knee/knee_identification.h"

using kneesim::diagnosis::Effect;
using namespace kneesim::test;

TEST_CASE("knee wear identification over many seeds") {
  const auto t = run_knee_wear_identification(
      {Effect::none, Effect::running_in, Effect::pressure_dependent_wear, Effect::cross_shear,
       Effect::creep},
      17000, 20, true);
  INFO(t.failures);
  CHECK(t.correct == t.runs);
  CHECK(t.false_positives == 0);
  CHECK(t.low_gain == 0);
  MESSAGE("knee wear (depth) " << t.correct << "/" << t.runs << ", smallest gain " << t.min_gain
                               << ", slowest " << t.max_seconds << " s");
  const auto v = run_knee_wear_identification(
      {Effect::none, Effect::running_in, Effect::pressure_dependent_wear, Effect::cross_shear},
      18000, 10, false);
  INFO(v.failures);
  CHECK(v.correct >= 0.9 * v.runs);
  CHECK(v.wrong_effect == 0);
  CHECK(v.false_positives == 0);
  MESSAGE("knee wear (volume only) " << v.correct << "/" << v.runs << ", smallest gain "
                                     << v.min_gain);
}

TEST_CASE("kinematics identification over several seeds") {
  const auto t = run_kinematics_identification(
      {Effect::none, Effect::friction, Effect::restraint}, 17200, 5);
  INFO(t.failures);
  MESSAGE(t.gains);
  CHECK(t.correct == t.runs);
  CHECK(t.false_positives == 0);
  CHECK(t.low_gain == 0);
  MESSAGE("kinematics " << t.correct << "/" << t.runs << ", smallest gain " << t.min_gain
                        << ", total " << t.total_seconds << " s");
}
