// The break-even wear factor of a material against a reference material (issue: a material
// comparison that does not borrow its answer). With no independent wear factor for a material,
// what kneesim can say is at which wear-factor ratio k / k_reference the material's volume (or,
// separately, its maximum depth) after the run equals the reference's on the same implant, rig
// and gait. Wear is not linear in k over a run with geometry updates (the worn insert conforms
// and its pressures fall, faster for a faster-wearing material), so the ratio is solved on the
// run itself: a secant in log(ratio) against log(result), which is nearly a straight line of
// slope 1, started from the material's own factor and its proportional correction.
//
// Each evaluation is one whole wear run (wear::run_wear, no files) of the material's built model
// with the law's coefficient set to ratio x the reference's factor; a run that stops early (the
// insert wore through) has no result at the run's length and counts as "above any target".
//
// The result grows with the ratio but not always smoothly: a run's time step adapts to the
// stiffening of the worn insert (wear/wear_loop.cpp), and whether and when it does is a
// threshold event, so a ratio change of 0.01 % can move the 5 Mc volume by 1 %. Once a ratio
// below the goal (lo) and one above it (hi) are known, the solve keeps them as a bracket and
// narrows it (interpolation, bisection when interpolation does not halve it); a bracket
// narrower than the tolerance is an answer even when no run lies within the tolerance of the
// goal: the result jumps across the goal inside it, and the break-even is that interval (its
// ends and their results are reported, never NaN).
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "models/build_model.h"
#include "wear/wear_loop.h"

namespace kneesim::run {

// one wear run at a factor ratio
struct RatioRun {
  double ratio = 0.0;          // k / k_reference [-]
  bool complete = false;       // false: stopped before the run's end (e.g. wore through)
  double volume_mm3 = 0.0;     // enclosed-volume loss at the end (or at the stop)
  double max_depth_mm = 0.0;
  double cycles = 0.0;         // cycles completed
  std::string failure;         // why it stopped, when it did
};

enum class BreakEvenTarget { kVolume, kMaxDepth };

struct BreakEven {
  BreakEvenTarget target = BreakEvenTarget::kVolume;
  double goal = 0.0;            // the reference's result (mm^3 or mm)
  // the solved ratio: a run within the tolerance of the goal, else (a bracket is known) the
  // geometric mean of the bracket; NaN only when no bracket is known
  double ratio = 0.0;
  double result = 0.0;          // the material's result at that ratio (NaN: not run there)
  // the closest ratios known below (lo) and above (hi) the goal and their results; lo = 0 or
  // hi = inf when not known (an early-stopped run above the goal has result_hi = inf)
  double lo = 0.0, hi = 0.0;
  double result_lo = 0.0, result_hi = 0.0;
  bool converged = false;       // within the tolerance of the goal, or a bracket that narrow
  bool jump = false;            // the result jumps across the goal inside [lo, hi]
  int runs = 0;                 // wear runs the solve needed (cached runs not counted)
  std::string note;             // how it was found when not by a run at the goal, or why not
};

// relative size of a jump [%]: result_hi / result_lo - 1
double jump_percent(const BreakEven& b);

// the runs of one material at several ratios, each made once (a solve and the plot's grid
// share them); not thread-safe: one per material and thread
class RatioRuns {
 public:
  // `options` is the material's wear run (law, friction, schedule); its law's coefficient (k
  // [m^2/N], or C of the contact-area law) is replaced by ratio x reference_factor
  RatioRuns(const models::BuiltModel& built, wear::WearOptions options, double reference_factor);
  // any result(ratio), e.g. a closed form for a test of the solve
  explicit RatioRuns(std::function<RatioRun(double ratio)> evaluate);
  const RatioRun& at(double ratio);
  // adds a run made elsewhere (e.g. the comparison's own run at the material's factor)
  void add(const RatioRun& run);
  std::vector<RatioRun> all() const;  // by ratio
  int made() const { return made_; }

 private:
  std::function<RatioRun(double ratio)> evaluate_;
  std::map<double, RatioRun> runs_;
  int made_ = 0;
};

struct BreakEvenOptions {
  double tolerance = 1e-3;  // |result / goal - 1|, or hi / lo - 1, at which the solve stops
  int max_runs = 14;
};

// solves result(ratio) = goal from the run at `start` (usually the material's own factor)
BreakEven solve_break_even(RatioRuns& runs, BreakEvenTarget target, double goal, double start,
                           const BreakEvenOptions& options = {});

// the figure of a run for a target (mm^3 or mm)
double target_value(const RatioRun& run, BreakEvenTarget target);
const char* target_name(BreakEvenTarget target);  // "volume", "max_depth"

}  // namespace kneesim::run
