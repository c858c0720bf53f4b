// Shared driver of the hidden-effect tests: runs the block-on-ring diagnosis on synthetic data
// sets of every applicable effect over a range of seeds and counts the identifications.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "analysis/diagnosis/effect.h"
#include "tests/diagnosis/identification_tally.h"

namespace kneesim::test {


constexpr double kMinGain = 0.2;  // required gain for a named effect [-]

// the effects of the block-on-ring tests: none, running_in, incubation,
// pressure_dependent_wear and (with depth) creep
std::vector<diagnosis::Effect> bor_test_effects(bool with_depth);

// seeds first_seed .. first_seed + seeds - 1 for each of `effects`
IdentificationTally run_identification(std::uint64_t first_seed, int seeds, bool with_depth,
                                       const std::vector<diagnosis::Effect>& effects);
inline IdentificationTally run_identification(std::uint64_t first_seed, int seeds,
                                              bool with_depth) {
  return run_identification(first_seed, seeds, with_depth, bor_test_effects(with_depth));
}

}  // namespace kneesim::test
