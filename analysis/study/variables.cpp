#include "analysis/study/variables.h"

#include <cstdio>

#include "engine/errors.h"

namespace kneesim::study {
namespace {

struct PalVariable {
  const char* label;
  const char* key;
  double sd;  // Pal 2008 table 1 [key's unit]
};

// physics.md section 8; FEax_AP's and FEax_IS's means (-5.5, 28 mm) are the NexGen
// component's own axis, here the implant's own reference (0)
constexpr PalVariable kPal2008[] = {
    {"FEax_AP", "rig.alignment.femur_fe_axis_ap_mm", 0.5},
    {"FEax_IS", "rig.alignment.femur_fe_axis_is_mm", 0.5},
    {"IEax_AP", "rig.alignment.tibia_ie_axis_ap_mm", 0.5},
    {"IEax_ML", "rig.alignment.tibia_ie_axis_ml_mm", 0.5},
    {"I_Fem_FE", "rig.alignment.femur_fe_deg", 1.0},
    {"Ins_Tilt", "rig.alignment.insert_tilt_deg", 1.0},
    {"Fem_IE", "rig.alignment.femur_ie_deg", 1.0},
    {"Fem_VV", "rig.femur_vv_deg", 1.0},
    {"Sprg_Gap", "rig.restraint.gap_mm", 0.5},
    {"K_Ant", "rig.restraint.k_anterior_N_per_mm", 0.09},
    {"K_Post", "rig.restraint.k_posterior_N_per_mm", 0.09},
    {"mu", "contact.friction", 0.01},
    {"k_w", "material.wear_factor_mm3_per_Nmm", 5.286e-12},
};

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string label_of(const std::string& key) {
  for (const PalVariable& p : kPal2008)
    if (key == p.key) return p.label;
  return key;
}

// truncates `v` to the key's range; InputError when that is not negligible and not allowed
void truncate_to_range(StudyVariable& v, const models::NumberKey& range, bool allow,
                       const std::string& where) {
  Distribution& d = v.distribution;
  const double lo = std::max(range.lo, d.lo), hi = std::min(range.hi, d.hi);
  v.removed_mass = mass_outside(d, lo, hi);
  if (d.kind == DistributionKind::kUniform && (d.lo < range.lo || d.hi > range.hi)) {
    throw InputError(where + ": " + describe(d) + " reaches outside the key's allowed range [" +
                     fmt(range.lo) + ", " + fmt(range.hi) + "]");
  }
  if (!(v.removed_mass < 1.0 - kNegligibleMass)) {
    throw InputError(where + ": " + describe(d) + " has no mass inside the key's allowed range [" +
                     fmt(range.lo) + ", " + fmt(range.hi) + "]");
  }
  if (v.removed_mass > kNegligibleMass && !allow) {
    throw InputError(where + ": " + describe(d) + " produces values outside the key's allowed "
                     "range [" + fmt(range.lo) + ", " + fmt(range.hi) + "] with probability " +
                     fmt(v.removed_mass) + "; narrow it, or pass --allow-truncation to sample "
                     "it truncated to that range");
  }
  if (d.kind != DistributionKind::kUniform) {
    d.lo = lo;
    d.hi = hi;
  }
}

}  // namespace

double nominal_value(const models::Config& base, const std::string& key) {
  if (key == "contact.friction" && base.friction_override < 0.0) return base.material.friction;
  const auto k = models::find_number_key(base, key);
  return k ? k->value : 0.0;
}

StudyVariable make_variable(const models::Config& base, const std::string& spec,
                            bool allow_truncation) {
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError("--var '" + spec + "' is not of the form key=distribution, e.g. "
                     "contact.friction=normal(nominal, 0.01)");
  }
  StudyVariable v;
  v.key = spec.substr(0, eq);
  const std::string where = "--var " + spec;
  const auto range = models::find_number_key(base, v.key);
  if (!range) {
    throw InputError(where + ": '" + v.key + "' is not a number key of the config (e.g. "
                     "rig.restraint.gap_mm, contact.friction, rig.alignment.insert_tilt_deg)");
  }
  v.label = label_of(v.key);
  v.nominal = nominal_value(base, v.key);
  v.distribution = parse_distribution(spec.substr(eq + 1), v.nominal, where);
  truncate_to_range(v, *range, allow_truncation, where);
  return v;
}

std::vector<StudyVariable> pal2008_variables(const models::Config& base, bool allow_truncation) {
  std::vector<StudyVariable> out;
  for (const PalVariable& p : kPal2008) {
    char spec[160];
    std::snprintf(spec, sizeof spec, "%s=normal(nominal, %.17g)", p.key, p.sd);
    out.push_back(make_variable(base, spec, allow_truncation));
  }
  return out;
}

}  // namespace kneesim::study
