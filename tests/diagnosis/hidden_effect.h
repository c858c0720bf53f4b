// Hidden-effect generator for the diagnosis tests: synthetic block-on-ring data sets at the
// sampling of Hussin 2024 (50k, 100k, 150k, 200k cycles; two loads, 225 N and 130 N; several
// specimens), with one hidden effect at a randomised magnitude, or none, plus specimen-to-
// specimen scatter of k and measurement noise. The data come from the reference forward path
// (KINSOL per point, CVODE for the pressure law), not from the table path the diagnosis fits
// with, so a test also checks that the two agree.
//
// Magnitude ranges (uniform), chosen as effects a test rig would report, not as limits of
// detectability:
//   running_in: extra volume 8-30 % of the 200k-cycle Archard volume (Hussin 2024: about
//               16 %), decay constant 5 000-20 000 cycles
//   pressure_dependent_wear: alpha 0.7-1.5 (1 = contact-area law)
//   creep: phi 0.3-1.0 of the elastic penetration, tau 0.5-3 h
//   incubation: N_i 10 000-40 000 cycles (a deficit of 5-20 % of the 200k-cycle Archard
//               volume, the size the paper's reading of Hussin 2024 implies: 12 %)
// Scatter: k of each specimen lognormal with 5 % CV; volume noise 0.02 mm^3 + 1 %, depth noise
// 2 um + 2 % (one standard deviation).
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "analysis/diagnosis/diagnosis_case.h"

namespace kneesim::test {

struct SyntheticOptions {
  int specimens_per_load = 6;         // [-]
  bool with_depth = true;             // measure penetration depth too
  double specimen_cv = 0.05;          // coefficient of variation of k between specimens [-]
  double volume_noise_mm3 = 0.02;     // absolute volume noise sd [mm^3]
  double volume_noise_rel = 0.01;     // relative volume noise sd [-]
  double depth_noise_mm = 0.002;      // absolute depth noise sd [mm]
  double depth_noise_rel = 0.02;      // relative depth noise sd [-]
};

struct SyntheticData {
  diagnosis::MeasuredData data;
  diagnosis::Effect truth = diagnosis::Effect::none;
  std::map<std::string, double> params;  // hidden parameters [I/O units]
};

SyntheticData make_synthetic_bor(diagnosis::Effect effect, std::uint64_t seed,
                                 const SyntheticOptions& options = {});

}  // namespace kneesim::test
