// The knee simulator as a study problem: a trial is the config with its variables set
// (`kneesim run --set key=value ...` reproduces it), its Model built on the nominal Model's
// geometry (implant, articular elements and femoral distance fields are shared; only the rig,
// contact, time step and static placement are rebuilt, models/build_model.h), then one gait run
// of config.cycles cycles (measures of the last) and, with wear, a wear run as `kneesim wear
// --cycles C --update-every C/U` computes it.
//
// Measures: ap_rom_mm, ie_rom_deg, peak_pressure_MPa (max over the cycle), and with wear
// max_linear_wear_mm and gravimetric_wear_mg at the end; curves: ap_mm and ie_deg at every 1 %
// of the cycle (envelopes.csv), and with wear the two wear measures after every update
// (wear_envelopes.csv).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "analysis/study/study.h"
#include "models/build_model.h"

namespace kneesim::study {

struct KneeStudySetup {
  std::string config;              // TOML path ("" = built-in defaults)
  std::vector<std::string> sets;   // key=value overrides applied to every trial
  std::vector<std::string> vars;   // key=distribution; empty = Pal 2008's 13
  std::string measured;            // measured kinematics to overlay ("" = the config's own)
  bool allow_truncation = false;
  bool wear = false;
  long wear_cycles = 5'000'000;
  int wear_updates = 10;
  bool quiet = false;              // no calibration messages (first use of a contact law)
};

// validates everything (variables, wear options) and builds the nominal Model; InputError
// before any trial runs
StudyProblem make_knee_problem(const KneeStudySetup& setup);

}  // namespace kneesim::study
