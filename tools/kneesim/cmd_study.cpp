// `kneesim study`: a probabilistic study (Pal 2008) over the knee simulator: Monte Carlo,
// Latin hypercube or advanced mean value, on all cores and, under mpirun, on every rank
// (the work is analysis/study).
#include <cstdio>
#include <sstream>

#include "analysis/study/knee_problem.h"
#include "analysis/study/ranks.h"
#include "analysis/study/study.h"
#include "engine/errors.h"
#include "engine/io/atomic_file.h"
#include "engine/io/output_folder.h"
#include "analysis/report/command_reports.h"
#include "tools/kneesim/commands.h"
#include "wear/checkpoint.h"
#include "wear/wear_law.h"

namespace kneesim::cli {
namespace {

struct StudyArgs {
  study::KneeStudySetup setup;
  std::string method = "mc";
  long trials = 100;
  unsigned long long seed = 1;
  std::string out = "kneesim-study";
  bool resume = false;
  int threads = 0;
  bool quiet = false;
  std::string wear_law;                 // "" = the config's wear.law
  std::vector<std::string> law_params;  // name=value
  bool no_calibrate = false;
};

// FNV-1a of a string through the checkpoint's hash (wear/checkpoint.h)
uint64_t fnv1a(const std::string& s) { return wear::fnv1a(s.data(), s.size()); }

void run(StudyArgs a) {
  study::Ranks ranks;  // MPI when launched by mpirun
  study::StudyOptions o;
  if (a.method == "mc") {
    o.method = study::Method::kMonteCarlo;
  } else if (a.method == "lhs") {
    o.method = study::Method::kLatinHypercube;
  } else if (a.method == "amv") {
    o.method = study::Method::kAdvancedMeanValue;
  } else {
    throw InputError("--method = '" + a.method + "' is not allowed (mc, lhs or amv)");
  }
  o.trials = a.trials;
  o.seed = a.seed;
  o.out = a.out;
  o.resume = a.resume;
  o.threads = a.threads;
  o.quiet = a.quiet || ranks.rank() != 0;
  // the wear-law shorthands are config overrides of every trial
  for (const models::Override& w : wear::wear_law_overrides(a.wear_law, a.law_params)) {
    a.setup.sets.push_back(w.key + "=" + w.value);
  }
  // the identity: everything that defines the study's trials (not threads, ranks or --out)
  std::ostringstream id;
  id << "study v1\n" << (a.setup.config.empty() ? std::string() : io::read_file(a.setup.config))
     << "\n";
  for (const auto& s : a.setup.sets) id << "set " << s << "\n";
  for (const auto& v : a.setup.vars) id << "var " << v << "\n";
  id << a.method << " " << (o.method == study::Method::kAdvancedMeanValue ? 0 : a.trials) << " "
     << a.seed << " " << a.setup.wear << " " << a.setup.wear_cycles << " "
     << a.setup.wear_updates << " " << a.setup.allow_truncation;
  o.identity = fnv1a(id.str());
  o.description = "kneesim study " + (a.setup.config.empty() ? std::string("(built-in config)")
                                                              : a.setup.config) +
                  " --method " + a.method;
  // every input is checked (and the nominal model built) before any trial runs
  const study::StudyProblem problem = study::make_knee_problem(a.setup);
  if (!o.quiet) {
    for (const auto& v : problem.variables) {
      // below 1e-6 (e.g. a normal's tail beyond 15 SD) the truncation is a technicality
      // (summary.json keeps every variable's truncated_mass)
      if (v.removed_mass > 1e-6) {
        std::fprintf(stderr, "%s: %s (probability mass removed %.3g)\n", v.key.c_str(),
                     study::describe(v.distribution).c_str(), v.removed_mass);
      }
    }
    std::fprintf(stderr, "kneesim study: %zu variables, method %s, %d rank(s)\n",
                 problem.variables.size(), a.method.c_str(), ranks.size());
  }
  const study::StudyResult r = study::run_study(problem, o, ranks);
  if (ranks.rank() == 0) report::write_study_report(a.out, a.method);
  if (!o.quiet) {
    std::printf("%zu trials (%ld failed, %ld resumed) in %.1f s, %.2f trials/s\nresults in %s\n",
                r.records.size(), r.failed, r.resumed, r.seconds,
                r.seconds > 0 ? static_cast<double>(r.computed) / r.seconds : 0.0,
                a.out.c_str());
  }
}

}  // namespace

void add_study_command(CLI::App& app) {
  auto args = std::make_shared<StudyArgs>();
  CLI::App* cmd = app.add_subcommand(
      "study",
      "Probabilistic study (Pal 2008): sample the input variables (default: Pal's 13 alignment, "
      "restraint, friction and wear-factor variables, centred on the config's own values), run "
      "the simulator per trial on all cores (and every rank under mpirun), and write "
      "DIR/trials.csv, DIR/envelopes.csv (AP and IE p01/p50/p99), DIR/sensitivity.csv "
      "(|Pearson r| per input and measure), DIR/summary.json and plots; with --wear also "
      "DIR/wear_envelopes.csv. Finished trials are journaled; --resume continues a killed study.");
  cmd->add_option("config", args->setup.config, "TOML config file")->check(CLI::ExistingFile);
  cmd->add_option("--method", args->method,
                  "mc (Monte Carlo), lhs (Latin hypercube) or amv (advanced mean value: 1 + n "
                  "gradient runs, then one corrected run per measure at p = 1 % and 99 %)")
      ->capture_default_str();
  cmd->add_option("--trials", args->trials, "trials (mc, lhs)")
      ->capture_default_str()->check(whole_range(2, 1e7));
  cmd->add_option("--seed", args->seed, "study seed (trial i's seed derives from it and i)")
      ->capture_default_str()->check(whole_range(0, kMaxSeed));
  cmd->add_option("--var", args->setup.vars,
                  "an input variable key=distribution (repeatable; replaces the default set): "
                  "normal(mean, sd), lognormal(mean, sd), uniform(lo, hi), truncnormal(mean, sd, "
                  "lo, hi); 'nominal' as the mean is the config's own value, e.g. "
                  "--var contact.friction=normal(nominal,0.01)");
  cmd->add_flag("--allow-truncation", args->setup.allow_truncation,
                "sample a distribution that reaches outside its key's allowed range truncated "
                "to that range (reported) instead of refusing it");
  cmd->add_option("--set", args->setup.sets, "override a config key for every trial (repeatable)");
  cmd->add_option("--measured", args->setup.measured,
                  "measured kinematics (CSV gait_pct,ap_mm,ie_deg or .sto) drawn over the AP and "
                  "IE envelopes (default: the config's output.measured_kinematics)");
  cmd->add_flag("--wear", args->setup.wear, "also run the wear simulation per trial");
  add_wear_law_options(cmd, args->wear_law, args->law_params);
  cmd->add_option("--wear-cycles", args->setup.wear_cycles, "wear cycles per trial")
      ->capture_default_str()->check(whole_range(1, 1e9));
  cmd->add_option("--wear-updates", args->setup.wear_updates, "geometry updates per wear trial")
      ->capture_default_str()->check(whole_range(1, 1000));
  cmd->add_option("--threads", args->threads, "threads per rank (0: OMP_NUM_THREADS or all cores)")
      ->capture_default_str()
      ->check(whole_range(0, 4096));
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_flag("--resume", args->resume,
                "continue the study in DIR from its journal (no finished trial is lost or run "
                "again)");
  cmd->add_flag("--quiet", args->quiet, "no progress or summary line");
  add_no_calibrate_flag(cmd, args->no_calibrate);
  cmd->callback([args] {
    args->setup.sets = with_no_calibrate(args->setup.sets, args->no_calibrate);
    args->setup.quiet = args->quiet;
    io::check_output_folder(args->out);  // before any work
    run(*args);
  });
}

}  // namespace kneesim::cli
