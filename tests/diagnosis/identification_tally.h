// The count of a hidden-effect identification run, shared by the block-on-ring
// (tests/diagnosis) and knee (tests/diagnosis_knee) drivers.
#pragma once

#include <string>

namespace kneesim::test {

struct IdentificationTally {
  int runs = 0;             // data sets diagnosed [-]
  int correct = 0;          // right effect named (including "none" for clean data) [-]
  int false_positives = 0;  // an effect named for clean data [-]
  int wrong_effect = 0;     // a different effect named for data with an effect [-]
  int low_gain = 0;         // right effect named but gain below the required gain [-]
  double min_gain = 1.0;    // smallest gain among the data sets with an effect [-]
  double max_seconds = 0.0; // slowest diagnosis [s]
  double total_seconds = 0.0;  // all diagnoses [s]
  // margins to the selection thresholds: the lowest dAICc of any effect on a clean set (a
  // false positive needs < -ic_threshold) and the highest dAICc of the true effect on a set
  // with an effect (a miss needs > -ic_threshold)
  double clean_min_daicc = 1e300;
  double effect_max_daicc = -1e300;
  // the same for the held-out RMSE relative to none's (selection needs < 1 - heldout_threshold)
  double clean_min_heldout_ratio = 1e300;
  double effect_max_heldout_ratio = -1e300;
  std::string failures;     // one line per wrong identification
  std::string gains;        // effect: gain per data set, for the log
};

}  // namespace kneesim::test
