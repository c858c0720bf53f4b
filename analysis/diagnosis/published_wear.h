// Diagnosis case for published summary data (kneesim diagnose published-wear): knee simulator
// wear rates reported as mean +- SD over n specimens per condition, one CSV per study with a
// config whose [conditions.<name>] tables reproduce each condition.
//
// Each wear law predicts every condition's wear rate from one simulated gait cycle per
// condition (the rate of the unworn insert; the kinematics do not depend on the law, so one
// simulation per condition serves all laws), first with parameters from sources independent of
// the data (a prediction, no fit), then with its coefficient calibrated on one condition of one
// study and predicting the rest (held out). The trivial predictor is the same rate under every
// condition (the calibration condition's measured mean). Scores are RMS log errors over the
// held-out conditions; their intervals come from moving every measured mean with an SD (the
// calibration condition's too) to the ends of its standard error, sd / sqrt(n), in every
// combination. A law is supported when it beats Archard and the trivial predictor over that
// whole interval; otherwise Archard stays. The calibration fits one unbounded scale and no
// shape parameter, so no fitted value can sit at a search bound.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "models/config.h"

namespace kneesim::diagnosis {

struct PublishedCondition {
  std::string condition;       // a [conditions.<name>] of the study's config
  double cycles = 0.0;         // test length [cycles]
  double mean = 0.0;           // wear rate [mm^3 / Mc]
  double sd = -1.0;            // SD over the specimens [mm^3 / Mc]; < 0: not published
  int n = 0;                   // specimens; 0: not published
  std::string note;
  int line = 0;                // of the CSV, for messages
  // standard error of the mean [mm^3 / Mc]; 0 when sd or n is unknown
  double sem() const;
};

struct PublishedStudy {
  std::string name;            // the CSV's stem, e.g. "barnett2001_wear"
  std::string source;          // CSV path
  std::string config_path;     // the study's config
  std::vector<PublishedCondition> rows;
};

// reads one study's CSV (columns condition, cycles, mean, sd, n, units[, note]; units
// mm3_per_Mc, or mm3 for a volume after `cycles`, converted to a rate); sd and n may be NA.
// Throws InputError naming the file, row, column, value and the allowed range (sd > 0, n >= 1)
PublishedStudy read_published_study(const std::string& csv, const std::string& config);

// a law as the case evaluates it: the [wear] overrides, where its parameters come from, and
// whether its coefficient is known independently (else only its ratios are a prediction)
struct PublishedLaw {
  std::string name;                         // wear.law
  std::vector<models::Override> overrides;  // wear.law and its parameters
  std::string source;                       // provenance of the parameters
  bool absolute = true;                     // the coefficient is independent of the data
};
// the laws of the case with the independent parameters docs/theory.md cites
std::vector<PublishedLaw> published_laws();

struct PublishedWearOptions {
  std::vector<std::string> sets;   // --set for every condition
  std::string calibration_study;   // "" = the first study
  std::string calibration_condition;  // "" = its first condition
};

// predicts every condition with every law and scores the predictions; throws InputError for a
// condition missing from its config and std::runtime_error when a simulation stops
nlohmann::json run_published_wear(const std::vector<PublishedStudy>& studies,
                                  const std::vector<PublishedLaw>& laws,
                                  const PublishedWearOptions& options);

// report.md, published_wear.csv, summary.json and (plots) published_wear.png into `out`;
// returns the report text
std::string write_published_wear(const nlohmann::json& result, const std::filesystem::path& out,
                                 bool plots);

}  // namespace kneesim::diagnosis
