// The kinetic/internal energy ratio of a cycle (engine/solid/energy_ratio.h) on hand-made
// series with known answers: the max over the loaded steps (internal energy at least a tenth
// of the cycle's largest), the cycle ratio (sum over sum), and the max after the start's
// settling steps, which a spike at the start (a run from rest) does not reach.
#include <doctest/doctest.h>

#include <vector>

#include "engine/solid/energy_ratio.h"

using kneesim::engine::solid::calc_energy_ratio;

TEST_CASE("energy ratio: loaded-step max, cycle ratio, and the max after the settling") {
  // 10 steps: a settling spike at step 1 (ratio 0.5), the loaded cycle at 0.01, one unloaded
  // step (internal 0.05 of the max) with a large ratio that the loaded-step rule leaves out
  const std::vector<double> internal = {0.2, 0.2, 1.0, 1.0, 1.0, 1.0, 0.05, 1.0, 1.0, 1.0};
  const std::vector<double> kinetic = {0.0, 0.1, 0.01, 0.01, 0.01, 0.01, 0.04, 0.01, 0.01, 0.01};
  const auto all = calc_energy_ratio(kinetic, internal);
  CHECK(all.max == doctest::Approx(0.5));
  CHECK(all.max_after_settling == doctest::Approx(0.5));  // no settling steps given
  double k = 0.0, u = 0.0;
  for (size_t i = 0; i < internal.size(); ++i) k += kinetic[i], u += internal[i];
  CHECK(all.cycle == doctest::Approx(k / u));
  const auto settled = calc_energy_ratio(kinetic, internal, 2);
  CHECK(settled.max == doctest::Approx(0.5));                // the max keeps the spike
  CHECK(settled.max_after_settling == doctest::Approx(0.01));  // the cycle's own
  CHECK(settled.cycle == doctest::Approx(all.cycle));
}
