#include "analysis/run/break_even.h"

#include <cmath>
#include <limits>

#include "wear/wear_law.h"

namespace kneesim::run {

double target_value(const RatioRun& run, BreakEvenTarget target) {
  return target == BreakEvenTarget::kVolume ? run.volume_mm3 : run.max_depth_mm;
}

const char* target_name(BreakEvenTarget target) {
  return target == BreakEvenTarget::kVolume ? "volume" : "max_depth";
}

RatioRuns::RatioRuns(const models::BuiltModel& built, wear::WearOptions options,
                     double reference_factor)
    : built_(built), options_(std::move(options)), reference_factor_(reference_factor) {
  // no files, no progress: only the records
  options_.checkpoint.clear();
  options_.resume = false;
  options_.progress = nullptr;
  options_.on_update = nullptr;
  options_.on_insert = nullptr;
}

void RatioRuns::add(const RatioRun& run) { runs_[run.ratio] = run; }

const RatioRun& RatioRuns::at(double ratio) {
  if (auto it = runs_.find(ratio); it != runs_.end()) return it->second;
  wear::WearOptions o = options_;
  wear::set_law_coefficient(o.law, ratio * reference_factor_);
  const wear::WearResult r = wear::run_wear(built_, o);
  ++made_;
  RatioRun run;
  run.ratio = ratio;
  run.complete = r.status == engine::StepStatus::kOk;
  run.failure = r.message;
  if (!r.records.empty()) {
    const wear::UpdateRecord& last = r.records.back();
    run.volume_mm3 = last.volume * 1e9;
    run.max_depth_mm = last.max_depth * 1e3;
    run.cycles = last.cycles;
  }
  return runs_[ratio] = run;
}

std::vector<RatioRun> RatioRuns::all() const {
  std::vector<RatioRun> out;
  for (const auto& [ratio, run] : runs_) out.push_back(run);
  return out;
}

BreakEven solve_break_even(RatioRuns& runs, BreakEvenTarget target, double goal, double start,
                           const BreakEvenOptions& options) {
  BreakEven b;
  b.target = target;
  b.goal = goal;
  b.ratio = std::numeric_limits<double>::quiet_NaN();
  if (!(goal > 0.0) || !(start > 0.0)) {
    b.note = "no reference result to match";
    return b;
  }
  const int made_before = runs.made();
  // the bracket: the largest ratio known below the goal, the smallest known above it (a run
  // that stopped early is above any goal)
  double lo = 0.0, hi = std::numeric_limits<double>::infinity();
  double x_prev = NAN, y_prev = NAN;  // log ratio, log result of the previous complete run
  double ratio = start;
  for (int i = 0; i <= options.max_runs; ++i) {
    const RatioRun& r = runs.at(ratio);
    const double y = target_value(r, target);
    if (!r.complete || !(y > 0.0)) {
      hi = std::min(hi, ratio);
      ratio = lo > 0.0 ? std::sqrt(lo * hi) : ratio / 10.0;  // bisect in log below the stop
      continue;
    }
    const double miss = y / goal - 1.0;
    if (std::abs(miss) <= options.tolerance) {
      b.ratio = ratio;
      b.result = y;
      b.runs = runs.made() - made_before;
      return b;
    }
    if (miss < 0.0) {
      lo = std::max(lo, ratio);
    } else {
      hi = std::min(hi, ratio);
    }
    const double x = std::log(ratio), ly = std::log(y);
    // secant in log-log; the first step (and a flat secant) assumes result proportional to k
    double slope = 1.0;
    if (std::isfinite(x_prev) && std::abs(x - x_prev) > 1e-12 && std::abs(ly - y_prev) > 1e-12) {
      slope = (ly - y_prev) / (x - x_prev);
    }
    if (!(slope > 0.05)) slope = 1.0;  // the result grows with k: never step the wrong way
    double next = std::exp(x + (std::log(goal) - ly) / slope);
    // stay inside the bracket
    if (next <= lo || next >= hi) next = lo > 0.0 && std::isfinite(hi) ? std::sqrt(lo * hi) : next;
    x_prev = x;
    y_prev = ly;
    ratio = next;
  }
  b.runs = runs.made() - made_before;
  b.note = "not within " + std::to_string(options.tolerance * 100.0) + " % after " +
           std::to_string(options.max_runs) + " runs";
  return b;
}

}  // namespace kneesim::run
