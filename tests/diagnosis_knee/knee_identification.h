// Shared driver of the knee hidden-effect tests: runs the knee-wear or kinematics diagnosis on
// synthetic data sets of every applicable effect over a range of seeds and counts the
// identifications (the generators and their magnitude ranges: knee_hidden_effect.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "analysis/diagnosis/effect.h"
#include "tests/diagnosis/identification_tally.h"

namespace kneesim::test {


constexpr double kKneeWearMinGain = 0.2;   // required gain of a named knee-wear effect [-]
constexpr double kKinematicsMinGain = 0.2; // required gain of a named kinematic effect [-]

// seeds first_seed .. first_seed + seeds - 1 for each effect in `effects`
IdentificationTally run_knee_wear_identification(const std::vector<diagnosis::Effect>& effects,
                                       std::uint64_t first_seed, int seeds, bool with_depth,
                                       int specimens = 0);  // 0: the design's kKneeSpecimens
// knee-wear data made by the wear loop (knee_loop_data.h): for each effect and seed one loop
// truth, then one data set per specimen scatter in `cvs`; each diagnosed with the forward
// model that follows the geometry (`path`) and, when `linear_too`, the pristine-linear one
// (`linear`); one tally per scatter
struct LoopTallies {
  std::vector<IdentificationTally> path, linear;
};
LoopTallies run_loop_identification(const std::vector<diagnosis::Effect>& effects,
                                    std::uint64_t first_seed, int seeds,
                                    const std::vector<double>& cvs, bool linear_too,
                                    int specimens = 3);

IdentificationTally run_kinematics_identification(const std::vector<diagnosis::Effect>& effects,
                                        std::uint64_t first_seed, int seeds);

}  // namespace kneesim::test
