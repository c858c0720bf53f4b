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
#include <functional>
#include <map>
#include <string>
#include <vector>

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

namespace kneesim::test {

// Block-on-ring data with measurement errors of families that are NOT the fit's error model
// (issue 27; the fit assumes a proportional sd a + b V, a specimen wear-factor effect and a
// constant soak-control offset per specimen):
//   walk        each weighing's error is the previous one's plus a new step (the soak-control
//               correction accumulates): a random walk over a specimen's measurements, steps of
//               sd (0.02 mm^3 + 1 % of the volume) / sqrt(2)
//   soak_drift  a per-specimen uptake error growing with time, o_s sqrt(N / 200 000), o_s of sd
//               0.04 mm^3, plus white noise of half the usual sd
//   heavy       Student-t errors with 3 degrees of freedom of the usual sd (outliers)
//   lognormal   multiplicative errors exp(0.03 z) - 1 plus 0.02 mm^3 white
// Depth keeps its white noise (2 um + 2 %). Specimen wear factors scatter by 5 % CV. The hidden
// effect's shape parameters are drawn from the ranges of make_synthetic_bor; its size parameter
// (running-in excess, pressure exponent, incubation time, creep ratio) is solved so that its
// identifiable signal (identifiable_signal_rms) is `ratio` times the set's noise RMS (the
// measured values minus the population model, specimen scatter included, in the diagnosis'
// RMSE measure).
enum class WearNoise { walk, soak_drift, heavy, lognormal };
const char* wear_noise_name(WearNoise n);
const std::vector<WearNoise>& all_wear_noises();

struct RatioSet {
  SyntheticData s;
  double noise_rms = 0.0;   // [rmse_unit]
  double signal_rms = 0.0;  // [rmse_unit]
};
RatioSet make_bor_at_ratio(diagnosis::Effect effect, double ratio, WearNoise kind,
                           std::uint64_t seed, bool with_depth);

// the size (a parameter between lo and hi, bisected in ln when `log`) at which the increasing
// function `signal` reaches `target`
double solve_size(const std::function<double(double)>& signal, double target, double lo,
                  double hi, bool log);

}  // namespace kneesim::test
