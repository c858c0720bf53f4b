// Shared driver of the hidden-effect tests: runs the block-on-ring diagnosis on synthetic data
// sets of every applicable effect over a range of seeds and counts the identifications.
#pragma once

#include <cstdint>
#include <string>

namespace kneesim::test {

struct IdentificationTally {
  int runs = 0;             // data sets diagnosed [-]
  int correct = 0;          // right effect named (including "none" for clean data) [-]
  int false_positives = 0;  // an effect named for clean data [-]
  int low_gain = 0;         // right effect named but gain below kMinGain [-]
  double min_gain = 1.0;    // smallest gain among the data sets with an effect [-]
  double max_seconds = 0.0; // slowest diagnosis [s]
  std::string failures;     // one line per wrong identification
};

constexpr double kMinGain = 0.2;  // required gain for a named effect [-]

// seeds first_seed .. first_seed + seeds - 1 for none, running_in, pressure_dependent_wear
// and (with depth) creep
IdentificationTally run_identification(std::uint64_t first_seed, int seeds, bool with_depth);

}  // namespace kneesim::test
