// The input variables of a knee study: any number key of the config, by name, with a
// distribution. The default set is Pal 2008's 13 (physics.md section 8), each centred on the
// config's own value (the implant's own reference for the alignment keys, the rig's gap and
// springs, the material's friction and wear factor) with Pal's SD, so any implant keeps the SDs.
//
// Every variable is truncated to its key's allowed range (the config's own physical limits:
// friction in [0, 1], stiffnesses >= 0, ...). When that removes more than kNegligibleMass of
// probability the distribution produces non-physical values: an input error before any trial
// runs, unless truncation is allowed; the removed mass is reported either way.
#pragma once

#include <string>
#include <vector>

#include "analysis/study/distribution.h"
#include "models/config.h"

namespace kneesim::study {

struct StudyVariable {
  std::string key;           // config key, e.g. "rig.alignment.insert_tilt_deg" (I/O units)
  std::string label;         // Pal 2008's name where it has one ("Ins_Tilt"), else the key
  Distribution distribution; // truncated to the key's range
  double nominal = 0.0;      // the config's own value [key's unit]
  double removed_mass = 0.0; // probability mass the truncation removed [-]
};

// "key=distribution" (distribution.h syntax); InputError for an unknown or non-number key,
// a bad distribution, or a non-physical one without `allow_truncation`
StudyVariable make_variable(const models::Config& base, const std::string& spec,
                            bool allow_truncation);

// Pal 2008's 13 variables on this config (mean = the config's value, Pal's SD)
std::vector<StudyVariable> pal2008_variables(const models::Config& base, bool allow_truncation);

// the config's effective value of a number key (contact.friction unset means the material's)
double nominal_value(const models::Config& base, const std::string& key);

}  // namespace kneesim::study
