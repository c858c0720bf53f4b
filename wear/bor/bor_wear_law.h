// Wear laws of the block-on-ring model: steady-state Archard (the practitioner's baseline) and
// the physically motivated extensions the diagnosis names (physics.md section 6, "what
// constant-k Archard gets wrong"). Pluggable through an enum class so that `kneesim bor
// --effect NAME` runs each extension forward, and the diagnosis fits the same code.
//
//   archard                  dV/dN = k F S
//   running_in               dV/dN = k F S (1 + a exp(-N / N_r))      extra early wear
//   pressure_dependent_wear  dV/dN = k (p / p_ref)^-alpha F S         p = mean contact
//                            pressure of the current (worn) geometry; alpha = 1 is the
//                            contact-area law of Abdelgaied 2011 (V ~ A S)
//   incubation               dV/dN = k F S (1 - exp(-N / N_i))        the wear rate rises from
//                            zero to the steady rate: an incubation period before steady wear
//                            (strain must accumulate before debris detaches); after a few N_i
//                            the volume lags the steady line by k F S N_i, a deficit
//                            proportional to the load
//   creep                    volume as archard; penetration depth gains
//                            phi delta_el(F) (1 - exp(-t / tau)), delta_el = unworn elastic
//                            penetration, t = test time: depth without volume loss (Zhao 2008)
//
// Cross-shear and friction need the kinematics of a knee; they live in the diagnosis effect
// library for the knee cases and are not BOR laws (a BOR ring slides in one direction only).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace kneesim::bor {

enum class BorWearLaw { archard, running_in, pressure_dependent_wear, creep, incubation };

struct BorWearParams {
  double k = 4.1e-16;                   // k_D steady-state wear factor (4.1e-10 mm^3/(N mm),
                                        // Hussin 2024) [m^3/(N m)]
  double running_in_excess = 1.0;       // a, initial extra wear-rate ratio [-]
  double running_in_cycles = 15000.0;   // N_r, running-in decay constant [cycles]
  double pressure_exponent = 1.0;       // alpha in k (p / p_ref)^-alpha [-]
  double reference_pressure = 5.8e6;   // p_ref (unworn mean pressure at 225 N) [Pa]
  double creep_ratio = 0.5;             // phi, saturated creep over elastic penetration [-]
  double creep_time = 3600.0;           // tau, creep time constant [s]
  double incubation_cycles = 25000.0;   // N_i, incubation time constant [cycles]
};

std::string_view wear_law_name(BorWearLaw law);
// parses "archard" (also "none"), "running_in", "pressure_dependent_wear", "creep",
// "incubation"; throws
// InputError naming `source` and the allowed names otherwise
BorWearLaw parse_wear_law(const std::string& name, const std::string& source);

// I/O names with units of the parameters a law adds to archard, e.g. "running_in_excess",
// "running_in_cycles" (empty for archard)
std::vector<std::string> wear_law_param_names(BorWearLaw law);
// sets one parameter from its I/O name and value in I/O units (MPa, s, cycles); throws
// InputError naming `source`, the parameter, the value and the allowed range
void set_wear_param(BorWearParams& p, const std::string& io_name, double io_value,
                    const std::string& source);
// value of a parameter in I/O units
double get_wear_param(const BorWearParams& p, const std::string& io_name);

// wear-rate multiplier on k F S at cycle count N and mean pressure p [Pa] [-]
double wear_rate_factor(BorWearLaw law, const BorWearParams& p, double cycles, double pressure);

// closed-form volume for the laws whose rate does not depend on the geometry (archard,
// running_in, creep, incubation) [m^3]; S = sliding distance per cycle [m]
double closed_form_volume(BorWearLaw law, const BorWearParams& p, double load, double sliding,
                          double cycles);

// creep penetration added to the scar depth [m]; delta_el = unworn penetration [m]
double creep_depth(BorWearLaw law, const BorWearParams& p, double delta_el, double time);

}  // namespace kneesim::bor
