// The time step of the wear loop's next cycle (wear::next_cycle_step, wear/wear_loop.h) against
// the central-difference limit dt_c = 2 / omega (sqrt(1 + z^2) - z), z = beta omega / 2
// (physics.md section 5; engine/simulate.h find_step_for_frequency):
//  - continuous in the measured frequency: frequencies 0.01 % apart give steps at most 0.01 %
//    plus one step per cycle apart, everywhere, also where the limit crosses the current step.
//    The policy it replaces shortened the step only above 90 % of the limit, to 80 % of it:
//    an 11 % jump of the step at a threshold, which made a 5 Mc volume jump by 1 % when the
//    wear factor moved by 0.01 % (the break-even solve of `kneesim compare`);
//  - never lengthens the step, and keeps it bit for bit while it is within the limit;
//  - whole steps per gait cycle, and within the limit for the frequency asked.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/model.h"
#include "engine/simulate.h"
#include "wear/wear_loop.h"

using namespace kneesim;

namespace {

engine::Model test_model() {
  engine::Model m;
  m.period = 1.2;
  m.dt = m.period / 4000.0;        // 3e-4 s
  m.contact.damping_beta = 2e-5;  // z = 0.05 at 5000 rad/s
  return m;
}

double limit(const engine::Model& m, double omega) {
  const double z = 0.5 * m.contact.damping_beta * omega;
  return 2.0 / omega * (std::sqrt(1.0 + z * z) - z);
}

}  // namespace

TEST_CASE("next cycle step: kept within the limit, never lengthened") {
  const engine::Model m = test_model();
  CHECK(wear::next_cycle_step(m, 100.0, 0.8) == m.dt);    // far within the limit
  CHECK(wear::next_cycle_step(m, 0.0, 0.8) == m.dt);      // no contact measured
  // the frequency at which 0.8 of the limit is the current step: kept
  double omega = 1000.0;
  while (0.8 * limit(m, omega) > m.dt) omega *= 1.0001;
  CHECK(wear::next_cycle_step(m, omega / 1.001, 0.8) == m.dt);
  for (double w : {omega * 1.01, omega * 1.5, omega * 4.0}) {
    const double dt = wear::next_cycle_step(m, w, 0.8);
    CHECK(dt < m.dt);
    CHECK(dt <= 0.8 * limit(m, w) * (1.0 + 1e-12));
    CHECK(dt > 0.8 * limit(m, w) * (1.0 - 1e-3));  // at most one step per cycle below it
    const double steps = m.period / dt;
    CHECK(std::abs(steps - std::round(steps)) < 1e-6);
  }
}

TEST_CASE("next cycle step: continuous in the measured frequency") {
  const engine::Model m = test_model();
  // from well within the limit (the current step kept) to 20 times the frequency at it,
  // including the stability ratios 0.8 (where the step starts to shorten) and 0.9 (where the
  // replaced policy shortened it by 11 % at once), in steps of 0.01 % of the frequency: the
  // step may change by as much (it is proportional to 1 / omega at most, the damping
  // correction making it less) plus one step per cycle of rounding (>= 3000 steps here)
  const double growth = 1.0001;
  double worst = 0.0;
  for (double w = 2000.0; w < 40000.0; w *= growth) {
    const double a = wear::next_cycle_step(m, w, 0.8);
    const double b = wear::next_cycle_step(m, w * growth, 0.8);
    CHECK(b <= a);
    worst = std::max(worst, std::abs(b / a - 1.0));
  }
  INFO("largest relative change of the step for a 0.01 % change of the frequency: " << worst);
  CHECK(worst < (growth - 1.0) + 1.0 / 3000.0);
}
