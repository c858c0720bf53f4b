// The break-even solve (analysis/run/break_even.h) on closed-form results, no simulation:
//  - a smooth power law: the solve stops at a ratio whose result is within the tolerance of
//    the goal (reference: the closed-form inverse, ratio = (goal / a)^(1 / n));
//  - a step function, the shape a wear run's result has where its time step adapts
//    differently (a 0.01 % change of the ratio moved the CFR-PEEK 5 Mc volume by 1 %): no ratio
//    gives the goal within the tolerance, and the solve reports the bracket around the step
//    (narrower than the tolerance, holding the step), the results at its ends and the jump,
//    never NaN;
//  - runs that stop early above a ratio: the bracket ends at the first stopped run;
//  - too few runs to narrow the bracket: the bracket is still reported (not converged).
#include <doctest/doctest.h>

#include <cmath>

#include "analysis/run/break_even.h"

using namespace kneesim::run;

namespace {

RatioRun complete_run(double ratio, double volume) {
  RatioRun r;
  r.ratio = ratio;
  r.complete = true;
  r.volume_mm3 = volume;
  r.max_depth_mm = 0.005 * volume;
  r.cycles = 5e6;
  return r;
}

// 69.04 mm^3 at 0.84696, 1 % more from kStep on: the measured CFR-PEEK case, in shape
constexpr double kStep = 0.847;
double step_volume(double ratio) { return 81.5 * ratio * (ratio < kStep ? 1.0 : 1.01); }

}  // namespace

TEST_CASE("break-even of a smooth result: a run within the tolerance") {
  RatioRuns runs([](double ratio) { return complete_run(ratio, 50.0 * std::pow(ratio, 1.1)); });
  const double goal = 42.0;
  const BreakEven b = solve_break_even(runs, BreakEvenTarget::kVolume, goal, 0.13);
  REQUIRE(std::isfinite(b.ratio));
  CHECK(b.converged);
  CHECK_FALSE(b.jump);
  CHECK(b.note.empty());
  CHECK(std::abs(b.result / goal - 1.0) <= 1e-3);
  CHECK(b.ratio == doctest::Approx(std::pow(goal / 50.0, 1.0 / 1.1)).epsilon(1e-3));
  CHECK(b.runs <= 5);
}

TEST_CASE("break-even across a step of the result: the bracket, its ends and the jump") {
  RatioRuns runs([](double ratio) { return complete_run(ratio, step_volume(ratio)); });
  // inside the step: below it the largest volume is 81.5 kStep, above it 1 % more
  const double goal = 81.5 * kStep * 1.005;
  const BreakEven b = solve_break_even(runs, BreakEvenTarget::kVolume, goal, 0.13);
  INFO(b.note);
  REQUIRE(std::isfinite(b.ratio));  // not NaN: the bracket is known
  CHECK(b.converged);
  CHECK(b.jump);
  CHECK(b.lo < kStep);
  CHECK(b.hi >= kStep);
  CHECK(b.hi / b.lo - 1.0 <= 1e-3);
  CHECK(b.ratio >= b.lo);
  CHECK(b.ratio <= b.hi);
  CHECK(b.result_lo == step_volume(b.lo));
  CHECK(b.result_hi == step_volume(b.hi));
  CHECK(b.result_lo < goal);
  CHECK(b.result_hi > goal);
  // the jump is the step (1 %) plus the slope over the bracket (at most 0.1 %)
  CHECK(jump_percent(b) > 1.0);
  CHECK(jump_percent(b) < 1.11);
  CHECK(b.note.find("volume jumps by 1") != std::string::npos);
  CHECK(b.note.find("between ratios") != std::string::npos);
  CHECK(b.runs <= BreakEvenOptions{}.max_runs);
}

TEST_CASE("break-even where the runs stop early: the bracket ends at the first stopped run") {
  // complete below 2 (volume 10 x ratio), worn through from 2 on: a goal of 25 is never met
  RatioRuns runs([](double ratio) {
    if (ratio < 2.0) return complete_run(ratio, 10.0 * ratio);
    RatioRun r;
    r.ratio = ratio;
    r.complete = false;
    r.volume_mm3 = 12.0;
    r.cycles = 1e6;
    return r;
  });
  const BreakEven b = solve_break_even(runs, BreakEvenTarget::kVolume, 25.0, 1.0);
  INFO(b.note);
  REQUIRE(std::isfinite(b.ratio));
  CHECK(b.lo < 2.0);
  CHECK(b.hi >= 2.0);
  CHECK(b.hi / b.lo - 1.0 <= 1e-3);
  CHECK(std::isinf(b.result_hi));
  CHECK(std::isnan(jump_percent(b)));
  CHECK(b.note.find("stops early") != std::string::npos);
}

TEST_CASE("break-even with too few runs to narrow the bracket: the bracket, not NaN") {
  RatioRuns runs([](double ratio) { return complete_run(ratio, step_volume(ratio)); });
  BreakEvenOptions few;
  few.max_runs = 3;
  const BreakEven b =
      solve_break_even(runs, BreakEvenTarget::kVolume, 81.5 * kStep * 1.005, 0.13, few);
  INFO(b.note);
  CHECK_FALSE(b.converged);
  REQUIRE(std::isfinite(b.ratio));
  CHECK(b.lo < kStep);
  CHECK(b.hi >= kStep);
  CHECK(b.note.find("lies between ratios") != std::string::npos);
  CHECK(b.runs == 3);
}

TEST_CASE("break-even without any ratio below the goal: NaN and why") {
  RatioRuns runs([](double ratio) { return complete_run(ratio, 100.0 + ratio); });
  BreakEvenOptions few;
  few.max_runs = 4;
  const BreakEven b = solve_break_even(runs, BreakEvenTarget::kVolume, 50.0, 1.0, few);
  CHECK(std::isnan(b.ratio));
  CHECK_FALSE(b.converged);
  CHECK(b.note.find("no ratio below") != std::string::npos);
}
