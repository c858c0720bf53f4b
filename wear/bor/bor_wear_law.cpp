#include "wear/bor/bor_wear_law.h"

#include <cmath>
#include <cstdio>

#include "engine/errors.h"

namespace kneesim::bor {

std::string_view wear_law_name(BorWearLaw law) {
  switch (law) {
    case BorWearLaw::archard: return "archard";
    case BorWearLaw::running_in: return "running_in";
    case BorWearLaw::pressure_dependent_wear: return "pressure_dependent_wear";
    case BorWearLaw::creep: return "creep";
    case BorWearLaw::incubation: return "incubation";
  }
  return "archard";
}

BorWearLaw parse_wear_law(const std::string& name, const std::string& source) {
  if (name == "archard" || name == "none") return BorWearLaw::archard;
  if (name == "running_in") return BorWearLaw::running_in;
  if (name == "pressure_dependent_wear") return BorWearLaw::pressure_dependent_wear;
  if (name == "creep") return BorWearLaw::creep;
  if (name == "incubation") return BorWearLaw::incubation;
  throw InputError(source + ": effect '" + name +
                   "' is not a block-on-ring wear law; allowed: none, running_in, "
                   "pressure_dependent_wear, creep, incubation.");
}

std::vector<std::string> wear_law_param_names(BorWearLaw law) {
  switch (law) {
    case BorWearLaw::archard: return {};
    case BorWearLaw::running_in: return {"running_in_excess", "running_in_cycles"};
    case BorWearLaw::pressure_dependent_wear:
      return {"pressure_exponent", "reference_pressure_MPa"};
    case BorWearLaw::creep: return {"creep_ratio", "creep_time_s"};
    case BorWearLaw::incubation: return {"incubation_cycles"};
  }
  return {};
}

namespace {

struct ParamDef {
  const char* name;
  double BorWearParams::*field;
  double to_si;  // SI value = I/O value * to_si
  double lo, hi;  // allowed I/O range, inclusive
};

constexpr ParamDef kParams[] = {
    {"running_in_excess", &BorWearParams::running_in_excess, 1.0, 0.0, 1e3},
    {"running_in_cycles", &BorWearParams::running_in_cycles, 1.0, 1.0, 1e8},
    {"pressure_exponent", &BorWearParams::pressure_exponent, 1.0, -5.0, 5.0},
    {"reference_pressure_MPa", &BorWearParams::reference_pressure, 1e6, 1e-3, 1e3},
    {"creep_ratio", &BorWearParams::creep_ratio, 1.0, 0.0, 100.0},
    {"creep_time_s", &BorWearParams::creep_time, 1.0, 1e-3, 1e9},
    {"incubation_cycles", &BorWearParams::incubation_cycles, 1.0, 1.0, 1e8},
};

const ParamDef& find_param(const std::string& io_name, const std::string& source) {
  for (const auto& d : kParams) {
    if (io_name == d.name) return d;
  }
  throw InputError(source + ": unknown effect parameter '" + io_name +
                   "'; allowed: running_in_excess, running_in_cycles, pressure_exponent, "
                   "reference_pressure_MPa, creep_ratio, creep_time_s, incubation_cycles.");
}

}  // namespace

void set_wear_param(BorWearParams& p, const std::string& io_name, double io_value,
                    const std::string& source) {
  const ParamDef& d = find_param(io_name, source);
  if (!std::isfinite(io_value) || io_value < d.lo || io_value > d.hi) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s: effect parameter %s = %g is outside the allowed range "
                  "[%g, %g].", source.c_str(), d.name, io_value, d.lo, d.hi);
    throw InputError(buf);
  }
  p.*d.field = io_value * d.to_si;
}

double get_wear_param(const BorWearParams& p, const std::string& io_name) {
  const ParamDef& d = find_param(io_name, "get_wear_param");
  return p.*d.field / d.to_si;
}

double wear_rate_factor(BorWearLaw law, const BorWearParams& p, double cycles, double pressure) {
  switch (law) {
    case BorWearLaw::archard:
    case BorWearLaw::creep: return 1.0;
    case BorWearLaw::running_in:
      return 1.0 + p.running_in_excess * std::exp(-cycles / p.running_in_cycles);
    case BorWearLaw::pressure_dependent_wear:
      return std::pow(pressure / p.reference_pressure, -p.pressure_exponent);
    case BorWearLaw::incubation: return -std::expm1(-cycles / p.incubation_cycles);
  }
  return 1.0;
}

double closed_form_volume(BorWearLaw law, const BorWearParams& p, double load, double sliding,
                          double cycles) {
  const double archard = p.k * load * sliding;  // per cycle [m^3]
  switch (law) {
    case BorWearLaw::archard:
    case BorWearLaw::creep: return archard * cycles;
    case BorWearLaw::running_in: {
      const double nr = p.running_in_cycles;
      return archard * (cycles + p.running_in_excess * nr * -std::expm1(-cycles / nr));
    }
    case BorWearLaw::incubation: {
      const double ni = p.incubation_cycles;
      return archard * (cycles - ni * -std::expm1(-cycles / ni));
    }
    case BorWearLaw::pressure_dependent_wear: break;
  }
  return NAN;  // geometry-dependent: integrated by simulate_bor
}

double creep_depth(BorWearLaw law, const BorWearParams& p, double delta_el, double time) {
  if (law != BorWearLaw::creep) return 0.0;
  return p.creep_ratio * delta_el * -std::expm1(-time / p.creep_time);
}

}  // namespace kneesim::bor
