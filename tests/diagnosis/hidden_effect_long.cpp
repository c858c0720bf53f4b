// Hidden-effect identification over many seeds (label "long"): 100 seeds per effect with
// depth (none, running_in, pressure_dependent_wear, creep) and 100 without depth (none,
// running_in, pressure_dependent_wear): 700 data sets. Required: 100 % identification, no
// false positive, every gain above kMinGain. Run: ctest -L long -R test_diagnosis_long.
#include <doctest/doctest.h>

#include "tests/diagnosis/identification.h"

using kneesim::test::kMinGain;
using kneesim::test::run_identification;

TEST_CASE("hidden effects over 100 seeds each are all identified") {
  for (const bool depth : {true, false}) {
    const auto t = run_identification(100000, 100, depth);
    INFO(t.failures);
    CAPTURE(depth);
    CHECK(t.correct == t.runs);
    CHECK(t.false_positives == 0);
    CHECK(t.low_gain == 0);
    MESSAGE("depth " << depth << ": identification " << t.correct << "/" << t.runs
                     << ", false positives " << t.false_positives << ", smallest gain "
                     << t.min_gain << ", slowest " << t.max_seconds << " s");
  }
}
