#include "analysis/study/study.h"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <mutex>

#include "analysis/study/statistics.h"
#include "analysis/study/study_outputs.h"
#include "engine/errors.h"
#include "engine/io/atomic_file.h"
#include "engine/io/journal_file.h"
#include "engine/io/progress.h"

namespace kneesim::study {
namespace {

// a planned trial: its inputs and how they were chosen
struct PlannedTrial {
  long index = 0;
  uint64_t seed = 0;
  std::string point;
  std::vector<double> inputs;
};

std::vector<double> at_nominal(const StudyProblem& p) {
  std::vector<double> x;
  for (const auto& v : p.variables) x.push_back(v.nominal);
  return x;
}

std::vector<double> from_z(const StudyProblem& p, const Eigen::VectorXd& z) {
  std::vector<double> x;
  for (size_t j = 0; j < p.variables.size(); ++j)
    x.push_back(from_standard_normal(p.variables[j].distribution, z[static_cast<Eigen::Index>(j)]));
  return x;
}

TrialRecord evaluate(const StudyProblem& p, const PlannedTrial& t) {
  TrialRecord r;
  r.index = t.index;
  r.seed = t.seed;
  r.point = t.point;
  r.inputs = t.inputs;
  TrialOutcome o;
  try {
    o = p.evaluate(t.inputs);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    o.ok = false;
    o.failure = e.what();
  }
  r.ok = o.ok;
  r.failure = o.ok ? o.note : o.failure;
  if (o.ok && o.scalars.size() == p.measures.size() && o.curves.size() == p.curves.size()) {
    r.scalars = o.scalars;
    r.curves = o.curves;
  } else {
    if (r.ok) r.failure = "the evaluation returned the wrong number of measures";
    r.ok = false;
    r.scalars.assign(p.measures.size(), std::numeric_limits<double>::quiet_NaN());
  }
  return r;
}

// runs the planned trials not yet in `done` over every rank and thread; returns all records
void run_trials(const StudyProblem& p, const StudyOptions& o, const Ranks& ranks,
                const std::vector<PlannedTrial>& planned, std::map<long, TrialRecord>& done,
                long& computed, io::ProgressBar& bar, long total, long& failed_seen,
                std::chrono::steady_clock::time_point t0) {
  std::vector<const PlannedTrial*> pending;
  for (const auto& t : planned)
    if (!done.count(t.index)) pending.push_back(&t);
  std::vector<const PlannedTrial*> mine;
  for (size_t k = 0; k < pending.size(); ++k)
    if (static_cast<int>(k % static_cast<size_t>(ranks.size())) == ranks.rank()) mine.push_back(pending[k]);

  const std::filesystem::path journal = journal_path(o.out, ranks.rank());
  std::mutex lock;
  std::vector<TrialRecord> finished(mine.size());
  long finished_here = 0;
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  std::exception_ptr error;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (long k = 0; k < static_cast<long>(mine.size()); ++k) {
    if (error) continue;
    try {
      TrialRecord r = evaluate(p, *mine[k]);
      const std::string line = to_journal_line(r);
      std::lock_guard<std::mutex> g(lock);
      io::append_line_durable(journal, line);
      if (!r.ok) ++failed_seen;
      finished[k] = std::move(r);
      ++finished_here;
      if (!o.quiet && ranks.rank() == 0) {
        const long all = static_cast<long>(done.size()) + finished_here * ranks.size();
        char detail[96];
        const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::snprintf(detail, sizeof detail, "%ld/%ld trials, %ld failed", std::min(all, total),
                      total, failed_seen);
        (void)el;
        bar.update(static_cast<double>(std::min(all, total)) / static_cast<double>(total), detail);
      }
    } catch (...) {
      std::lock_guard<std::mutex> g(lock);
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
  // gather every rank's records
  std::string lines;
  for (const auto& r : finished) lines += to_journal_line(r);
  for (const std::string& part : ranks.all_gather(lines)) {
    size_t pos = 0;
    while (pos < part.size()) {
      const size_t nl = part.find('\n', pos);
      TrialRecord r;
      if (from_journal_line(part.substr(pos, nl - pos), r)) {
        done[r.index] = std::move(r);
        ++computed;
      }
      pos = nl + 1;
    }
  }
}

}  // namespace

const char* method_name(Method m) {
  switch (m) {
    case Method::kMonteCarlo: return "mc";
    case Method::kLatinHypercube: return "lhs";
    case Method::kAdvancedMeanValue: return "amv";
  }
  return "";
}

StudyResult run_study(const StudyProblem& p, const StudyOptions& o, const Ranks& ranks) {
  namespace fs = std::filesystem;
  const auto t0 = std::chrono::steady_clock::now();
  const int n = static_cast<int>(p.variables.size());
  if (n == 0) throw InputError("the study has no input variables");
  if (o.method != Method::kAdvancedMeanValue && (o.trials < 2 || o.trials > 10000000)) {
    throw InputError("--trials = " + std::to_string(o.trials) + " is not allowed (2 to 1e7)");
  }
  if (!(o.amv_step > 0.0 && o.amv_step <= 3.0)) {
    throw InputError("the AMV step = " + std::to_string(o.amv_step) + " is outside (0, 3]");
  }
  ranks.require_same(o.identity, "the study (config, options, variables)");

  std::map<long, TrialRecord> done;
  if (ranks.rank() == 0) fs::create_directories(o.out);
  if (o.resume) {
    done = read_journals(o.out, o.identity);
  } else if (ranks.rank() == 0) {
    remove_journals(o.out);
    clear_study_outputs(o.out);
  }
  ranks.all_gather("");  // every rank sees the cleared folder before writing its journal
  const fs::path journal = journal_path(o.out, ranks.rank());
  if (!fs::exists(journal) || fs::file_size(journal) == 0)
    io::append_line_durable(journal, journal_header(o.identity));

  StudyResult result;
  result.resumed = static_cast<long>(done.size());
  for (const auto& [i, r] : done)
    if (!r.ok) ++result.failed;
  long failed_seen = result.failed;
  io::ProgressBar bar(std::string("study ") + method_name(o.method));

  // the nominal trial (every variable at its nominal value) for the plots; not a sample
  {
    PlannedTrial t;
    t.index = -1;
    t.point = "nominal";
    t.inputs = at_nominal(p);
    result.nominal = evaluate(p, t);
  }

  std::vector<PlannedTrial> planned;
  if (o.method == Method::kAdvancedMeanValue) {
    // stage 1: the mean point and one step per variable
    planned.push_back({0, 0, "mean", from_z(p, Eigen::VectorXd::Zero(n))});
    for (int j = 0; j < n; ++j) {
      Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
      z[j] = o.amv_step;
      planned.push_back({j + 1, 0, "grad:" + p.variables[j].label, from_z(p, z)});
    }
    const long total = n + 1 + static_cast<long>(p.measures.size() * o.amv_levels.size());
    run_trials(p, o, ranks, planned, done, result.computed, bar, total, failed_seen, t0);
    for (long i = 0; i <= n; ++i) {
      if (!done.at(i).ok) {
        throw std::runtime_error("the AMV design run " + done.at(i).point + " failed (" +
                                 done.at(i).failure + "); the mean-value model needs it");
      }
    }
    // stage 2: one corrected run per measure and level, at the linear model's MPP
    long index = n + 1;
    for (size_t m = 0; m < p.measures.size(); ++m) {
      std::vector<double> steps;
      for (int j = 1; j <= n; ++j) steps.push_back(done.at(j).scalars[m]);
      const MeanValueModel mv = make_mean_value_model(done.at(0).scalars[m], steps, o.amv_step);
      for (double level : o.amv_levels) {
        char name[128];
        std::snprintf(name, sizeof name, "mpp:%s:p%02.0f", p.measures[m].c_str(), 100 * level);
        planned.push_back({index++, 0, name, from_z(p, most_probable_point(mv, level))});
      }
    }
    run_trials(p, o, ranks, planned, done, result.computed, bar, total, failed_seen, t0);
  } else {
    LatinHypercubePlan lhs;
    if (o.method == Method::kLatinHypercube) lhs = make_latin_hypercube(o.seed, o.trials, n);
    for (long i = 0; i < o.trials; ++i) {
      PlannedTrial t;
      t.index = i;
      t.seed = trial_seed(o.seed, i);
      const std::vector<double> u = sample_unit(o.method, o.seed, i, n, &lhs);
      for (int j = 0; j < n; ++j) t.inputs.push_back(quantile(p.variables[j].distribution, u[j]));
      planned.push_back(std::move(t));
    }
    run_trials(p, o, ranks, planned, done, result.computed, bar, o.trials, failed_seen, t0);
  }
  bar.finish();
  for (auto& [i, r] : done) result.records.push_back(std::move(r));
  result.failed = 0;
  for (const auto& r : result.records)
    if (!r.ok) ++result.failed;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (ranks.rank() == 0) {
    write_study_outputs(p, o, result);
    remove_journals(o.out);
  }
  return result;
}

}  // namespace kneesim::study
