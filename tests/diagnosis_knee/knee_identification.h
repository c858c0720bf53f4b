// Shared driver of the knee hidden-effect tests: runs the knee-wear or kinematics diagnosis on
// synthetic data sets of every applicable effect over a range of seeds and counts the
// identifications (the generators and their magnitude ranges: knee_hidden_effect.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "analysis/diagnosis/effect.h"

namespace kneesim::test {

struct KneeTally {
  int runs = 0;             // data sets diagnosed [-]
  int correct = 0;          // right effect named (including "none" for clean data) [-]
  int false_positives = 0;  // an effect named for clean data [-]
  int wrong_effect = 0;     // a different effect named for data with an effect [-]
  int low_gain = 0;         // right effect named but gain below the threshold [-]
  double min_gain = 1.0;    // smallest gain among the data sets with an effect [-]
  double max_seconds = 0.0; // slowest diagnosis [s]
  double total_seconds = 0.0;  // all diagnoses [s]
  // margins to the selection thresholds: the lowest dAICc of any effect on a clean set and
  // the highest dAICc of the true effect on a set with an effect
  double clean_min_daicc = 1e300;
  double effect_max_daicc = -1e300;
  // the same for the held-out RMSE relative to none's (selection needs < 1 - heldout_threshold)
  double clean_min_heldout_ratio = 1e300;
  double effect_max_heldout_ratio = -1e300;
  std::string failures;     // one line per wrong identification
  std::string gains;        // effect: gain per data set, for the log
};

constexpr double kKneeWearMinGain = 0.2;   // required gain of a named knee-wear effect [-]
constexpr double kKinematicsMinGain = 0.2; // required gain of a named kinematic effect [-]

// seeds first_seed .. first_seed + seeds - 1 for each effect in `effects`
KneeTally run_knee_wear_identification(const std::vector<diagnosis::Effect>& effects,
                                       std::uint64_t first_seed, int seeds, bool with_depth,
                                       int specimens = 0);  // 0: the design's kKneeSpecimens
KneeTally run_kinematics_identification(const std::vector<diagnosis::Effect>& effects,
                                        std::uint64_t first_seed, int seeds);

}  // namespace kneesim::test
