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
#pragma once

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
  double ratio = 0.0;           // solved ratio; NaN when not found
  double result = 0.0;          // the material's result at that ratio
  int runs = 0;                 // wear runs the solve needed (cached runs not counted)
  std::string note;             // why it was not found, when it was not
};

// the runs of one material at several ratios, each made once (a solve and the plot's grid
// share them); not thread-safe: one per material and thread
class RatioRuns {
 public:
  // `options` is the material's wear run (law, friction, schedule); its law's coefficient (k
  // [m^2/N], or C of the contact-area law) is replaced by ratio x reference_factor
  RatioRuns(const models::BuiltModel& built, wear::WearOptions options, double reference_factor);
  const RatioRun& at(double ratio);
  // adds a run made elsewhere (e.g. the comparison's own run at the material's factor)
  void add(const RatioRun& run);
  std::vector<RatioRun> all() const;  // by ratio
  int made() const { return made_; }

 private:
  const models::BuiltModel& built_;
  wear::WearOptions options_;
  double reference_factor_;
  std::map<double, RatioRun> runs_;
  int made_ = 0;
};

struct BreakEvenOptions {
  double tolerance = 1e-3;  // |result / goal - 1| at which the solve stops
  int max_runs = 10;
};

// solves result(ratio) = goal from the run at `start` (usually the material's own factor)
BreakEven solve_break_even(RatioRuns& runs, BreakEvenTarget target, double goal, double start,
                           const BreakEvenOptions& options = {});

// the figure of a run for a target (mm^3 or mm)
double target_value(const RatioRun& run, BreakEvenTarget target);
const char* target_name(BreakEvenTarget target);  // "volume", "max_depth"

}  // namespace kneesim::run
