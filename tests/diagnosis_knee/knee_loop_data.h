// Knee-wear data made by the geometry-updating wear loop (wear::run_wear, what `kneesim wear`
// runs), not by the diagnosis' own tables (issue 14 item 6): the test that the knee-wear
// diagnosis names a hidden law in data it did not make itself.
//
// Design (the experiment the issue describes): the four conditions of knee_conditions.toml
// (iso, low_ie, high_load, low_load), `specimens` per condition (3 by default, the design that
// was named `none` under a hidden pressure law), 0.25, 0.5, 1, 1.5, 2, 3 Mc.
// Hidden laws, one per data set, magnitudes uniform in:
//   none
//   pressure_dependent_wear: alpha 0.7-1.5, p_ref the iso condition's mean pressure
//                            (wear::WearLaw::kPressureDependent, per step and element)
//   cross_shear: the iso condition wears 40-100 % more than without cross-shear
//                (wear::WearLaw::kCrossShear)
//   running_in: extra volume 10-30 % of the 3 Mc volume, N_r 1e5-4e5 cycles (the loop
//               scales each update's depth by its effective cycles)
// k = 2.643e-10 mm^3/(N mm) x U(0.8, 1.25). Specimens: k_s = k exp(cv z), z standard normal,
// cv = the specimen scatter (5-15 % in the tests). One loop per condition at the data set's k
// (updates every 0.4 Mc to 6 Mc); a specimen's curve is the loop's at N k_s / k (exact for a
// law whose rate is k times a function of the worn geometry: the specimen walks the same
// geometries, faster), for running-in at N_eff(N) k_s / k of the Archard loop (the loop's
// running-in is a factor on each update's depth); linear between updates. Noise: volume
// 0.2 mm^3 + 2 % (one standard deviation).
#pragma once

#include <cstdint>
#include <vector>

#include "tests/diagnosis_knee/knee_hidden_effect.h"

namespace kneesim::test {

// one condition's wear-loop curve at the data set's k
struct LoopCurve {
  std::vector<double> cycles;  // after each update, 0 first [cycles]
  std::vector<double> volume;  // depth integral [mm^3]
  double at(double n) const;   // linear between updates, the last slope beyond [mm^3]
};

// the hidden law of one data set and its loop curves per condition (the expensive part,
// shared by data sets that differ only in specimens and noise)
struct LoopTruth {
  diagnosis::Effect truth = diagnosis::Effect::none;
  std::map<std::string, double> params;    // hidden parameters [I/O units]
  double k = 0.0;                           // [m^2/N]
  double running_in_excess = 0.0, running_in_cycles = 0.0;  // [-], [cycles]
  std::map<std::string, LoopCurve> curves;  // per condition
  double seconds = 0.0;                     // loop wall time [s]
};

LoopTruth make_loop_truth(diagnosis::Effect effect, std::uint64_t seed);

// specimens and noise on a truth
KneeSynthetic make_loop_knee_wear(const LoopTruth& truth, std::uint64_t seed, double specimen_cv,
                                  int specimens = 3);

// worn geometry states of the tests' forward tables
constexpr int kKneePathStates = 4;

// forward tables that follow the geometry (kKneePathStates worn states) of the four test
// conditions, reaching past the largest volume any test set can hold (built once per process)
const diagnosis::KneeWearTables& knee_test_path_tables();

// the conditions of the test design
const std::vector<std::string>& knee_test_conditions();

}  // namespace kneesim::test
