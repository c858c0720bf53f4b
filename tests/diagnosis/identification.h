// Shared driver of the hidden-effect tests: runs the block-on-ring diagnosis on synthetic data
// sets of every applicable effect over a range of seeds and counts the identifications.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "analysis/diagnosis/effect.h"

namespace kneesim::test {

struct IdentificationTally {
  int runs = 0;             // data sets diagnosed [-]
  int correct = 0;          // right effect named (including "none" for clean data) [-]
  int false_positives = 0;  // an effect named for clean data [-]
  int low_gain = 0;         // right effect named but gain below kMinGain [-]
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
};

constexpr double kMinGain = 0.2;  // required gain for a named effect [-]

// the effects of the block-on-ring tests: none, running_in, pressure_dependent_wear and (with
// depth) creep
std::vector<diagnosis::Effect> bor_test_effects(bool with_depth);

// seeds first_seed .. first_seed + seeds - 1 for each of `effects`
IdentificationTally run_identification(std::uint64_t first_seed, int seeds, bool with_depth,
                                       const std::vector<diagnosis::Effect>& effects);
inline IdentificationTally run_identification(std::uint64_t first_seed, int seeds,
                                              bool with_depth) {
  return run_identification(first_seed, seeds, with_depth, bor_test_effects(with_depth));
}

}  // namespace kneesim::test
