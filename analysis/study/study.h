// The study driver: samples the input variables (Monte Carlo, Latin hypercube or the advanced
// mean value design), evaluates the trials on all threads of every rank, journals each finished
// trial, and writes the results (study_outputs.h). The evaluation is a function of the input
// values only, so the driver serves the knee simulator (knee_problem.h) and analytic functions
// (the tests) alike.
//
// Determinism: trial i's inputs depend on (seed, i, N) alone and the evaluation on its inputs
// alone, so trials.csv is byte-identical for any thread and rank count, serial or parallel,
// interrupted and resumed or not. A failed trial (numerical trouble) is recorded with its
// reason, counted, and left out of the statistics.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/study/ranks.h"
#include "analysis/study/sampling.h"
#include "analysis/study/trial_record.h"
#include "analysis/study/variables.h"
#include "engine/io/table.h"

namespace kneesim::study {

// what one evaluation returns
struct TrialOutcome {
  bool ok = true;
  std::string failure;                       // why it stopped (ok = false)
  std::string note;                          // a remark on an ok trial (e.g. a shortened step)
  std::vector<double> scalars;               // one per StudyProblem::measures
  std::vector<std::vector<double>> curves;   // one per StudyProblem::curves
};

// a sampled curve of every trial (AP over the gait cycle, wear against cycles)
struct CurveSpec {
  std::string name;             // e.g. "ap_mm"
  std::string x_name;           // e.g. "gait_pct"
  std::vector<double> x;        // sample positions
  std::string file;             // envelope file it goes to ("envelopes.csv")
};

struct StudyProblem {
  std::vector<StudyVariable> variables;
  std::vector<std::string> measures;  // scalar measure names with units
  std::vector<CurveSpec> curves;
  // measured curves shown with the envelopes (DIR/measured_kinematics.csv: the first curve's
  // x name and any curve names); no columns when there are none
  io::Table measured;
  // thread-safe; x: one value per variable [key's unit]
  std::function<TrialOutcome(const std::vector<double>& x)> evaluate;
  // the nominal config's rigid contact law and its provenance (summary.json)
  nlohmann::json contact_law;
};

struct StudyOptions {
  Method method = Method::kMonteCarlo;
  long trials = 100;                   // MC and LHS
  uint64_t seed = 1;
  std::vector<double> amv_levels{0.01, 0.99};  // probability levels of the AMV percentiles
  double amv_step = 1.0;               // forward-difference step in standard normal space [-]
  int threads = 0;                     // 0: OpenMP's default
  std::filesystem::path out;
  bool resume = false;
  bool quiet = false;
  uint64_t identity = 0;               // hash of everything that defines the study
  std::string description;             // one line for summary.json (config, options)
};

struct StudyResult {
  std::vector<TrialRecord> records;    // by index
  TrialRecord nominal;                 // every variable at its nominal value
  long resumed = 0;                    // records restored from the journals
  long computed = 0;                   // trials evaluated by this launch (all ranks)
  long failed = 0;
  double seconds = 0.0;
};

// runs (or resumes) the study and, on rank 0, writes its outputs; returns the result on every
// rank. Throws InputError for bad options before any trial runs.
StudyResult run_study(const StudyProblem& problem, const StudyOptions& options,
                      const Ranks& ranks);

const char* method_name(Method m);

}  // namespace kneesim::study
