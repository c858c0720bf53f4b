// `kneesim diagnose published-wear`: published knee simulator wear (mean +- SD, n per
// condition) against every wear law (analysis/diagnosis/published_wear.h).
#include "tools/kneesim/diagnose_published.h"

#include <cstdio>
#include <memory>

#include "analysis/diagnosis/published_wear.h"
#include "engine/errors.h"
#include "engine/io/output_folder.h"

namespace kneesim::cli {
namespace {

struct PublishedOptions {
  std::vector<std::string> studies;  // DATA.csv=CONFIG.toml
  std::vector<std::string> sets;
  std::string calibrate;             // STUDY:CONDITION
  std::string out = "kneesim-diagnose-published";
  bool no_plots = false;
};

void run_published(const PublishedOptions& o) {
  std::vector<diagnosis::PublishedStudy> studies;
  for (const std::string& s : o.studies) {
    const size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == s.size()) {
      throw InputError("command line: --study '" + s + "' is not of the form DATA.csv=CONFIG.toml");
    }
    studies.push_back(diagnosis::read_published_study(s.substr(0, eq), s.substr(eq + 1)));
  }
  diagnosis::PublishedWearOptions po;
  po.sets = o.sets;
  if (!o.calibrate.empty()) {
    const size_t colon = o.calibrate.find(':');
    if (colon == std::string::npos) {
      throw InputError("command line: --calibrate '" + o.calibrate + "' is not of the form "
                       "STUDY:CONDITION (STUDY = the data file's name without .csv)");
    }
    po.calibration_study = o.calibrate.substr(0, colon);
    po.calibration_condition = o.calibrate.substr(colon + 1);
  }
  const nlohmann::json r =
      diagnosis::run_published_wear(studies, diagnosis::published_laws(), po);
  std::printf("%s\nresults in %s\n",
              diagnosis::write_published_wear(r, o.out, !o.no_plots).c_str(), o.out.c_str());
}

}  // namespace

void add_diagnose_published_wear(CLI::App* diagnose) {
  auto opt = std::make_shared<PublishedOptions>();
  CLI::App* cmd = diagnose->add_subcommand(
      "published-wear",
      "published knee simulator wear rates (CSV per study: condition, cycles, mean, sd, n, "
      "units, note) against every wear law: independent prediction, one condition calibrated, "
      "the rest held out; writes DIR/report.md, DIR/published_wear.csv, DIR/summary.json, "
      "DIR/published_wear.png");
  cmd->add_option("--study", opt->studies,
                  "DATA.csv=CONFIG.toml: a study's data and the config whose [conditions.<name>] "
                  "tables reproduce its conditions (repeatable)")
      ->required();
  cmd->add_option("--calibrate", opt->calibrate,
                  "STUDY:CONDITION whose measured mean calibrates each law's coefficient "
                  "(default: the first study's first condition)");
  cmd->add_option("--set", opt->sets, "override a config key for every condition (repeatable)");
  cmd->add_option("--out", opt->out, "output folder")->capture_default_str();
  cmd->add_flag("--no-plots", opt->no_plots, "skip DIR/published_wear.png");
  cmd->callback([opt] {
    io::check_output_folder(opt->out);  // before any work
    run_published(*opt);
  });
}

}  // namespace kneesim::cli
