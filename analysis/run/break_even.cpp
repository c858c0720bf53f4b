#include "analysis/run/break_even.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "wear/wear_law.h"

namespace kneesim::run {

double target_value(const RatioRun& run, BreakEvenTarget target) {
  return target == BreakEvenTarget::kVolume ? run.volume_mm3 : run.max_depth_mm;
}

const char* target_name(BreakEvenTarget target) {
  return target == BreakEvenTarget::kVolume ? "volume" : "max_depth";
}

double jump_percent(const BreakEven& b) {
  if (!b.jump || !std::isfinite(b.result_hi) || !(b.result_lo > 0.0)) return std::nan("");
  return 100.0 * (b.result_hi / b.result_lo - 1.0);
}

RatioRuns::RatioRuns(const models::BuiltModel& built, wear::WearOptions options,
                     double reference_factor) {
  // no files, no progress: only the records
  options.checkpoint.clear();
  options.resume = false;
  options.progress = nullptr;
  options.on_update = nullptr;
  options.on_insert = nullptr;
  evaluate_ = [&built, options = std::move(options), reference_factor](double ratio) {
    wear::WearOptions o = options;
    wear::set_law_coefficient(o.law, ratio * reference_factor);
    const wear::WearResult r = wear::run_wear(built, o);
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
    return run;
  };
}

RatioRuns::RatioRuns(std::function<RatioRun(double ratio)> evaluate)
    : evaluate_(std::move(evaluate)) {}

void RatioRuns::add(const RatioRun& run) { runs_[run.ratio] = run; }

const RatioRun& RatioRuns::at(double ratio) {
  if (auto it = runs_.find(ratio); it != runs_.end()) return it->second;
  RatioRun run = evaluate_(ratio);
  run.ratio = ratio;
  ++made_;
  return runs_[ratio] = run;
}

std::vector<RatioRun> RatioRuns::all() const {
  std::vector<RatioRun> out;
  for (const auto& [ratio, run] : runs_) out.push_back(run);
  return out;
}

namespace {

std::string fmt(const char* f, double a, double b = 0.0, double c = 0.0, double d = 0.0,
                double e = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d, e);
  return buf;
}

}  // namespace

BreakEven solve_break_even(RatioRuns& runs, BreakEvenTarget target, double goal, double start,
                           const BreakEvenOptions& options) {
  BreakEven b;
  b.target = target;
  b.goal = goal;
  b.ratio = std::numeric_limits<double>::quiet_NaN();
  b.result = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  b.lo = 0.0;
  b.hi = inf;
  b.result_lo = 0.0;
  b.result_hi = inf;
  if (!(goal > 0.0) || !(start > 0.0)) {
    b.note = "no reference result to match";
    return b;
  }
  const int made_before = runs.made();
  const char* what = target_name(target);
  double x_prev = NAN, y_prev = NAN;  // log ratio, log result of the previous complete run
  double last_width = inf;            // log(hi / lo) before the last evaluation
  double ratio = start;
  for (int i = 0; i < options.max_runs; ++i) {
    const RatioRun& r = runs.at(ratio);
    const double y = target_value(r, target);
    const bool stopped = !r.complete || !(y > 0.0);
    if (!stopped && std::abs(y / goal - 1.0) <= options.tolerance) {
      b.ratio = ratio;
      b.result = y;
      b.converged = true;
      b.runs = runs.made() - made_before;
      return b;
    }
    // the bracket: the largest ratio known below the goal, the smallest known above it (a run
    // that stopped early is above any goal)
    if (!stopped && y < goal) {
      if (ratio > b.lo) b.lo = ratio, b.result_lo = y;
    } else if (ratio < b.hi) {
      b.hi = ratio;
      b.result_hi = stopped ? inf : y;
    }
    const bool bracketed = b.lo > 0.0 && std::isfinite(b.hi);
    if (bracketed && b.hi / b.lo - 1.0 <= options.tolerance) {
      // no run within the tolerance, yet the ratio is known to it: the result jumps across
      // the goal between two ratios closer than the tolerance
      b.ratio = std::sqrt(b.lo * b.hi);
      b.converged = true;
      b.jump = true;
      b.runs = runs.made() - made_before;
      if (!std::isfinite(b.result_hi)) {
        b.note = "the run stops early (e.g. wears through) from ratio " + fmt("%.6g", b.hi) +
                 " on, while at " + fmt("%.6g", b.lo) + " its " + what + " is " +
                 fmt("%.4g", b.result_lo) + ": the break-even is that interval";
        return b;
      }
      b.note = std::string(what) + " jumps by " + fmt("%.2g", jump_percent(b)) +
               " % between ratios " + fmt("%.6g and %.6g (%.4g to %.4g", b.lo, b.hi, b.result_lo,
                                               b.result_hi) +
               (target == BreakEvenTarget::kVolume ? " mm^3" : " mm") +
               "): no ratio gives the reference's " + what + " within " +
               fmt("%.2g", 100.0 * options.tolerance) + " %; the break-even is that interval";
      return b;
    }
    double next;
    if (bracketed) {
      // interpolate log(result) between the bracket's ends; bisect (in log ratio) when the
      // last step did not halve the bracket or an end stopped early
      const double width = std::log(b.hi / b.lo);
      const double x_lo = std::log(b.lo), x_hi = std::log(b.hi);
      next = std::sqrt(b.lo * b.hi);
      if (std::isfinite(b.result_hi) && width <= 0.5 * last_width) {
        const double f = (std::log(goal) - std::log(b.result_lo)) /
                         (std::log(b.result_hi) - std::log(b.result_lo));
        // keep off the ends so that a one-sided approach still narrows the bracket
        next = std::exp(x_lo + std::clamp(f, 0.05, 0.95) * (x_hi - x_lo));
      }
      last_width = width;
    } else if (stopped) {
      next = b.lo > 0.0 ? std::sqrt(b.lo * b.hi) : ratio / 10.0;
    } else {
      // secant in log-log; the first step (and a flat secant) assumes result proportional to k
      const double x = std::log(ratio), ly = std::log(y);
      double slope = 1.0;
      if (std::isfinite(x_prev) && std::abs(x - x_prev) > 1e-12 &&
          std::abs(ly - y_prev) > 1e-12) {
        slope = (ly - y_prev) / (x - x_prev);
      }
      if (!(slope > 0.05)) slope = 1.0;  // the result grows with k: never step the wrong way
      next = std::exp(x + (std::log(goal) - ly) / slope);
      if (next <= b.lo || next >= b.hi) next = b.lo > 0.0 ? 2.0 * b.lo : 0.5 * b.hi;
    }
    if (!stopped) {
      x_prev = std::log(ratio);
      y_prev = std::log(y);
    }
    ratio = next;
  }
  b.runs = runs.made() - made_before;
  const std::string tol = fmt("%.2g", 100.0 * options.tolerance);
  if (b.lo > 0.0 && std::isfinite(b.hi)) {
    b.ratio = std::sqrt(b.lo * b.hi);
    b.note = std::string(what) + " not within " + tol + " % of the reference's after " +
             std::to_string(options.max_runs) + " runs; the break-even lies between ratios " +
             fmt("%.6g and %.6g (%.4g to %.4g)", b.lo, b.hi, b.result_lo, b.result_hi);
  } else {
    b.note = std::string(what) + " not within " + tol + " % of the reference's after " +
             std::to_string(options.max_runs) + " runs, and no ratio " +
             (b.lo > 0.0 ? "above" : "below") + " it was found";
  }
  return b;
}

}  // namespace kneesim::run
