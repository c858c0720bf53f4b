// Synthetic instrumented-knee data for the forces diagnosis tests (issue 27): four load cells
// (PM, AM, AL, PL) whose true forces come from a direct simulation of the rig with a hidden
// effect (or none), driven by clean ISO 14243-1-shaped loads (two cycles, the second 7 %
// lighter), plus instrument errors of one of several families, NONE of which is the fit's
// error model (an Ornstein-Uhlenbeck process with an offset, a linear drift and proportional
// gain and crosstalk terms):
//   white_walk  per cell white noise (10 N) plus a random-walk drift (2 N per sample)
//   resonant    per cell AR(2) resonance at 7 Hz (sd 12 N, decay 0.15 s) plus a constant offset
//               U(-15, 15) N
//   crosstalk   crosstalk between NON-neighbouring cells (PM<->AL, AM<->PL) of 3-6 %, cell
//               gains 1 + N(0, 0.02), white noise 8 N
//   pink        1/f-like: four AR(1) components (5, 20, 80, 320 ms, 7 N each) per cell
//   harmonic    per cell two sinusoids at random frequencies 1.5-6 Hz (10 N, random phase)
//               plus white noise 5 N
// The medial reading is PM + AM, the rig's input the sum of the four cells (both with the
// errors, as an instrumented tray measures them). The anterior/posterior split within each
// compartment moves over the cycle (the contact migrates). Sampled at 100 Hz, 0-2.25 s;
// cycle 1 is [0.10, 1.10) s.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "analysis/diagnosis/forces_diagnosis.h"
#include "models/config.h"
#include "tests/loads/temp_dir.h"

namespace kneesim::test {

enum class CellNoise { white_walk, resonant, crosstalk, pink, harmonic };
const char* cell_noise_name(CellNoise n);
const std::vector<CellNoise>& all_cell_noises();

struct ForcesSet {
  diagnosis::ForcesMeasured measured;   // read back from the written table
  std::string file;                     // the table
  double noise_rms = 0.0;               // RMS of (measured - true) medial force over the rows [N]
  double value = 0.0;                   // hidden effect parameter [I/O unit]
  double signal_rms = 0.0;              // identifiable signal of the hidden effect [N]
  double noise_scale = 1.0;             // factor on the family's noise [-]
};

// the synthetic bench: the clean loads, the config, and a simulator of the clean loads for the
// truth (built once)
class ForcesBench {
 public:
  ForcesBench();
  // a data set with the hidden effect at `value` and noise `kind` from `seed`
  ForcesSet make(diagnosis::Effect truth, double value, CellNoise kind, std::uint64_t seed,
                 double noise_scale = 1.0);
  // a data set with the hidden effect at a value drawn from its test range (load_line and
  // vv_moment 1-3 mm, vv_alignment 1-2.5 deg, either sign) and the noise of `kind` scaled so that
  // the effect's identifiable signal is `ratio` times the set's noise RMS; for none, the
  // family's noise at the amplitude of a ratio-1.2 set of a 2.5 mm load-line shift
  ForcesSet make_at_ratio(diagnosis::Effect truth, double ratio, CellNoise kind,
                          std::uint64_t seed);
  // the diagnosis of a set (a simulator driven by the set's own filtered loads)
  diagnosis::ForcesDiagnosisReport diagnose(const ForcesSet& s,
                                            const diagnosis::DiagnosisOptions& options);
  // the identifiable signal of `truth` at `value` on the clean record [N]
  double signal(diagnosis::Effect truth, double value);
  const models::Config& config() const { return config_; }
  const std::string& config_path() const { return config_path_; }
  TempDir& dir() { return tmp_; }

 private:
  TempDir tmp_;
  std::string config_path_;
  models::Config config_;
  diagnosis::ForcesMeasured clean_;
  std::shared_ptr<diagnosis::ForcesSimulator> clean_sim_;
  int written_ = 0;
  std::map<diagnosis::Effect, std::shared_ptr<diagnosis::DiagnosisCase>> signal_cases_;
};

}  // namespace kneesim::test
