#include "wear/wear_law.h"

#include <cmath>
#include <cstdlib>

#include "engine/errors.h"
#include "wear/archard.h"

namespace kneesim::wear {
namespace {

struct LawName {
  WearLaw law;
  std::string_view name;
};
// material_pressure is the pressure-dependent kernel with the material's own exponent and
// p_ref (make_wear_law); the first name of a law is its name in outputs
constexpr LawName kLawNames[] = {
    {WearLaw::kArchard, "archard"},
    {WearLaw::kPressureDependent, "pressure_dependent_wear"},
    {WearLaw::kPressureDependent, "material_pressure"},
    {WearLaw::kCrossShear, "cross_shear"},
    {WearLaw::kContactArea, "contact_area"},
    {WearLaw::kRunningIn, "running_in"},
    {WearLaw::kIncubation, "incubation"},
};

}  // namespace

std::string_view wear_law_name(WearLaw law) {
  for (const LawName& n : kLawNames)
    if (n.law == law) return n.name;
  return "archard";
}

WearLaw parse_wear_law(const std::string& name, const std::string& source) {
  std::string allowed;
  for (const LawName& n : kLawNames) {
    if (n.name == name) return n.law;
    allowed += (allowed.empty() ? "" : ", ") + std::string(n.name);
  }
  throw InputError(source + ": wear law '" + name + "' does not exist (allowed: " + allowed + ")");
}

WearLawParams make_wear_law(const models::WearConfig& config, const models::BuiltModel& built) {
  return make_wear_law(config, built.material, built.model.contact.friction);
}

WearLawParams make_wear_law(const models::WearConfig& c, const models::MaterialConfig& m,
                            double friction) {
  WearLawParams p;
  p.law = parse_wear_law(c.law, "wear.law");
  p.wear_factor = m.wear_factor_mm3_per_Nmm * kWearFactorSI;
  p.area_coefficient = m.area_wear_coefficient;
  p.friction = friction;
  p.beta = c.cross_shear_gain;
  p.alpha = c.pressure_exponent;
  p.p_ref = c.reference_pressure_MPa * 1e6;
  p.running_in_excess = c.running_in_excess;
  p.running_in_cycles = c.running_in_cycles;
  p.incubation_cycles = c.incubation_cycles;
  p.creep = c.creep;
  p.creep_ratio = c.creep_ratio;
  p.creep_time = c.creep_time_s;
  if (c.law == "material_pressure") {  // k = k_ref (p / p_ref)^n: alpha = -n
    p.alpha = -m.wear_pressure_exponent;
    p.p_ref = m.wear_reference_pressure_MPa * 1e6;
  }
  if (p.law == WearLaw::kContactArea && !(p.area_coefficient > 0.0)) {
    throw InputError("material '" + m.name + "' has no area_wear_coefficient (0), which wear.law "
                     "= \"contact_area\" needs; allowed: a number in (0, 1e-3] as "
                     "material.area_wear_coefficient or in its [materials." + m.name + "] table");
  }
  return p;
}

std::vector<models::Override> wear_law_overrides(const std::string& law,
                                                 const std::vector<std::string>& params) {
  std::vector<models::Override> out;
  if (!law.empty()) out.push_back({"wear.law", "\"" + law + "\""});
  for (const std::string& text : params) {
    const size_t eq = text.find('=');
    std::string name = text.substr(0, eq);
    char* end = nullptr;
    const char* value = eq == std::string::npos ? "" : text.c_str() + eq + 1;
    const double v = std::strtod(value, &end);
    if (eq == std::string::npos || end == value || *end != '\0' || !std::isfinite(v)) {
      throw InputError("--law-param '" + text + "' is not of the form name=number");
    }
    if (name == "alpha") name = "pressure_exponent";
    if (name == "p_ref_MPa") name = "reference_pressure_MPa";
    if (name == "beta") name = "cross_shear_gain";
    if (name == "law" || name == "creep") {
      throw InputError("--law-param '" + text + "': '" + name + "' is not a law parameter (use "
                       "--wear-law, or --set wear.creep=true)");
    }
    out.push_back({"wear." + name, value});
  }
  return out;
}

double law_coefficient(const WearLawParams& law) {
  return law.law == WearLaw::kContactArea ? law.area_coefficient : law.wear_factor;
}

void set_law_coefficient(WearLawParams& law, double coefficient) {
  (law.law == WearLaw::kContactArea ? law.area_coefficient : law.wear_factor) = coefficient;
}

double creep_depth(const WearLawParams& law, double elastic_penetration, double time) {
  if (!law.creep || !(elastic_penetration > 0.0)) return 0.0;
  return law.creep_ratio * elastic_penetration * -std::expm1(-time / law.creep_time);
}

double effective_cycles(const WearLawParams& law, double n0, double n) {
  switch (law.law) {
    case WearLaw::kRunningIn: {
      if (law.running_in_cycles <= 0.0) return n;
      const double nr = law.running_in_cycles;
      return n + law.running_in_excess * nr * (std::exp(-n0 / nr) - std::exp(-(n0 + n) / nr));
    }
    case WearLaw::kIncubation: {
      if (law.incubation_cycles <= 0.0) return n;
      const double ni = law.incubation_cycles;
      return n - ni * (std::exp(-n0 / ni) - std::exp(-(n0 + n) / ni));
    }
    case WearLaw::kArchard:
    case WearLaw::kPressureDependent:
    case WearLaw::kCrossShear:
    case WearLaw::kContactArea: break;
  }
  return n;
}

}  // namespace kneesim::wear
