// Hidden-effect generators for the knee diagnosis tests: synthetic measured data made by the
// SAME forward models the diagnosis fits, with one hidden effect at a randomised magnitude (or
// none) plus specimen and measurement scatter.
//
// Knee wear (conditions of tests/diagnosis_knee/knee_conditions.toml: iso, low_ie (IE torque
// x 0.25: cross-shear contrast), high_load and low_load (axial force x 1.6 and x 0.5: mean
// pressure +26 % and -28 %, the pressure contrast a test of a pressure law needs); 6 specimens
// each (kKneeSpecimens); 0.25, 0.5, 1, 1.5, 2, 3 Mc):
//   k = 2.643e-10 mm^3/(N mm) x U(0.8, 1.25); specimen k lognormal 5 % CV
//   running_in: extra volume 10-30 % of the 3 Mc volume, N_r 1e5-4e5 cycles
//   pressure_dependent_wear: alpha 0.7-1.5 (p_ref: the iso condition's mean pressure)
//   cross_shear: the iso condition wears 40-100 % more than without cross-shear
//   creep: phi 0.5-1.5 of the elastic penetration, tau 2e4-2e5 s
//   noise: volume 0.2 mm^3 + 2 %, depth 3 um + 3 % (one standard deviation)
// Kinematics (generic implant, stanmore rig, 3 mm elements, one simulated cycle per
// evaluation): measured AP and IE every 2 %:
//   friction: mu 0.02-0.035 or 0.14-0.22 (nominal 0.07)
//   restraint: stiffness scale 0.25-0.5 or 2.5-5, gap 1-5 mm
//   registration offsets U(-1, 1) mm and deg; noise 0.15 mm and 0.25 deg (white)
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "analysis/diagnosis/kinematics_sim.h"
#include "analysis/diagnosis/knee_wear_case.h"
#include "tests/diagnosis/hidden_effect.h"

namespace kneesim::test {

struct KneeSynthetic {
  diagnosis::MeasuredData data;
  diagnosis::Effect truth = diagnosis::Effect::none;
  std::map<std::string, double> params;  // hidden parameters [I/O units]
};

// the config of the knee tests (tests/diagnosis_knee/knee_conditions.toml)
std::string knee_test_config();

// the forward tables of the four test conditions (simulated once per process)
const diagnosis::KneeWearTables& knee_test_tables();

// specimens per condition of the test design: with 3, a cross-shear or pressure effect at the
// low end of its range stands only about 5 standard errors of the condition means above the
// specimen scatter (5 % CV), and 1 in 400 volume-only sets was named `none` (docs/diagnosis.md)
constexpr int kKneeSpecimens = 6;

KneeSynthetic make_synthetic_knee_wear(diagnosis::Effect effect, std::uint64_t seed,
                                       bool with_depth, int specimens = kKneeSpecimens);

// the kinematics simulator of the test rig (built once per process)
std::shared_ptr<diagnosis::KinematicsSimulator> kinematics_test_simulator();

KneeSynthetic make_synthetic_kinematics(diagnosis::Effect effect, std::uint64_t seed);

// Knee wear with measurement errors that are not the fit's error model (issue 27): the design
// of make_synthetic_knee_wear (four conditions, six specimens, 0.25-3 Mc, specimen wear factors
// 5 % CV) with the measurement error of one family of tests/diagnosis/hidden_effect.h
// (WearNoise: walk, soak_drift, heavy, lognormal; volume sd 0.2 mm^3 + 2 %, soak offsets
// of sd 0.8 mm^3 growing as sqrt(N / 3 Mc), depth white 3 um + 3 %), and the hidden effect's
// size parameter (running-in excess, pressure exponent, cross-shear gain, creep ratio) solved so
// that its identifiable signal is `ratio` times the set's noise RMS (measured minus the
// population model, specimen scatter included)
struct KneeRatioSet {
  KneeSynthetic s;
  double noise_rms = 0.0;
  double signal_rms = 0.0;
};
KneeRatioSet make_knee_wear_at_ratio(diagnosis::Effect effect, double ratio, WearNoise kind,
                                     std::uint64_t seed, bool with_depth);

// Kinematics with correlated measurement errors (issue 27), families that are NOT the fit's
// error model (an Ornstein-Uhlenbeck process per channel with a prior-bound rotation-centre
// term):
//   registration  registration offsets U(-1, 1) mm and deg (the baseline's offsets absorb them;
//                 not counted as noise) and a rotation centre r = +-U(3, 8) mm off the rig's IE
//                 axis: AP += r sin(IE); white 0.1 mm and 0.15 deg
//   smooth        per channel a Fourier error over the cycle, harmonics 1-3 of amplitude
//                 0.15/h mm and 0.25/h deg at random phases; white 0.05 mm and 0.08 deg
//   walk          per channel a random walk over the samples (steps 0.05 mm, 0.08 deg); white
//                 0.05 mm and 0.08 deg
// The hidden effect's value is drawn from a test range (friction 0.025-0.045 or 0.11-0.18,
// restraint stiffness scale 0.35-0.6 or 1.7-3 with gap 1-5 mm), and the noise is scaled so
// that the effect's identifiable signal is `ratio` times the noise RMS (the diagnosis' RMSE
// measure). For none, the noise of a ratio-1.2 set with friction 0.035.
enum class KinematicsNoise { registration, smooth, walk };
const char* kinematics_noise_name(KinematicsNoise n);
const std::vector<KinematicsNoise>& all_kinematics_noises();

struct KinematicsSet {
  KneeSynthetic s;
  double noise_rms = 0.0;    // of the scaled noise [ap_mm units]
  double signal_rms = 0.0;   // identifiable signal of the hidden effect [ap_mm units]
  double scale = 1.0;        // factor on the family's noise [-]
  // the same noise (draw and scale) and registration offsets without the hidden effect: the
  // clean data of this noise regime, whose reported detection limit the effect's onset is
  // compared with (the rotation-centre term grows with the scale against the error model's
  // fixed prior, so clean sets at another scale are another regime)
  KneeSynthetic twin;
};
KinematicsSet make_kinematics_at_ratio(diagnosis::Effect effect, double ratio, KinematicsNoise kind,
                                       std::uint64_t seed);

}  // namespace kneesim::test
