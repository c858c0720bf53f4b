// The knee wear laws (theory: wear laws) as one value, WearLawParams, built from the config's
// [wear] section and the insert material by make_wear_law(): `kneesim run` (wear-rate maps),
// `wear`, `compare`, `study` wear trials and the diagnosis forward models all take it from
// here, so a law has the same name and parameters everywhere. Per element e and time step:
//
//   archard                  dh = k p ds s(mu)                      s(mu) = sqrt(1 + 3 mu^2)
//   pressure_dependent_wear  dh = k (p / p_ref)^-alpha p ds s(mu)   (Mazzucco & Spector 2003)
//   material_pressure        the same with the material's own k = k_ref (p / p_ref)^n: alpha = -n
//                            and p_ref from models/materials.toml (wear_pressure_exponent, ...)
//   cross_shear              dh = k f(CS_e) (p / p_ref)^-alpha p ds s(mu)
//                            f(CS) = 1 + g CS, CS_e the element's cross-shear ratio over the
//                            cycle (frictional-work tensor, Kang 2008); alpha = 0 unless given
//   contact_area             dh = C f(CS_e) ds while the element is in contact: the volume
//                            C f(CS) A S of Abdelgaied 2011, independent of the load
//   running_in, incubation   archard with the cycles weighted (effective_cycles)
//
// The coefficient (k, or C for contact_area) is the material's; the wear potential is what the
// law multiplies it by. Creep (any law, wear.creep = true) adds a penetration
// phi d_el (1 - exp(-t / tau)) that grows with the element's cycle-mean elastic penetration
// d_el and the loaded time t and saturates at phi d_el: reported beside the wear depth, never
// part of the worn volume or the geometry.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "models/build_model.h"
#include "models/config.h"

namespace kneesim::wear {

enum class WearLaw {
  kArchard,            // constant k (the baseline)
  kPressureDependent,  // k (p / p_ref)^-alpha
  kCrossShear,         // k f(CS) (p / p_ref)^-alpha
  kContactArea,        // C f(CS) per unit sliding distance in contact, no pressure
  kRunningIn,          // dV/dN = k F S (1 + a exp(-N / N_r)): extra early wear (Hussin 2024)
  kIncubation,         // dV/dN = k F S (1 - exp(-N / N_i)): the rate rises to steady state
};

struct WearLawParams {
  WearLaw law = WearLaw::kArchard;
  double wear_factor = 0.0;        // k or k_ref [m^2/N]
  double area_coefficient = 0.0;   // C of the contact-area law [-]
  double friction = 0.07;          // mu in the Sarkar factor [-]
  double p_ref = 10e6;             // reference pressure of the pressure factor [Pa]
  double alpha = 0.0;              // exponent of the pressure factor [-]
  double beta = 0.0;               // cross-shear gain g [-]
  double running_in_excess = 0.0;  // a, initial extra wear-rate ratio [-]
  double running_in_cycles = 2e5;  // N_r, running-in decay constant [cycles]
  double incubation_cycles = 2e5;  // N_i, incubation time constant [cycles]
  bool creep = false;              // creep penetration reported beside wear
  double creep_ratio = 0.5;        // phi, saturated creep over elastic penetration [-]
  double creep_time = 3600.0;      // tau [s]
};

// config name of a law ("archard", "cross_shear", ...)
std::string_view wear_law_name(WearLaw law);
// the law named `name`; throws InputError naming `source` and the allowed names
WearLaw parse_wear_law(const std::string& name, const std::string& source);

// the law of `config` ([wear]) for `material` (its k and C) and friction mu [-]; throws
// InputError when the law needs a coefficient the material lacks (contact_area with C = 0)
WearLawParams make_wear_law(const models::WearConfig& config,
                            const models::MaterialConfig& material, double friction);

// the law a simulation of `built` wears its insert by: the config's [wear] law with the built
// insert material's coefficients and the contact's friction. The one call `kneesim wear`,
// compare, study and the knee-wear diagnosis forward model take their law from, so that the
// same config gives the same law everywhere
WearLawParams make_wear_law(const models::WearConfig& config, const models::BuiltModel& built);

// the `--wear-law NAME` and `--law-param name=value` shorthands as config overrides
// (wear.law, wear.<name>); the diagnosis' short names alpha, p_ref_MPa and beta are accepted
std::vector<models::Override> wear_law_overrides(const std::string& law,
                                                 const std::vector<std::string>& params);

// the coefficient the law multiplies its wear potential by: C [-] for contact_area, k [m^2/N]
// for the others; set_law_coefficient replaces it (a material's ratio to another's)
double law_coefficient(const WearLawParams& law);
void set_law_coefficient(WearLawParams& law, double coefficient);

// the cross-shear factor f(CS) = 1 + g CS [-]
inline double cross_shear_factor(double cross_shear_ratio, double gain) {
  return 1.0 + gain * cross_shear_ratio;
}

// creep penetration [m] after loaded time t [s] for cycle-mean elastic penetration d_el [m]
double creep_depth(const WearLawParams& law, double elastic_penetration, double time);

// the cycles [n0, n0 + n] weighted by the law's wear-rate factor: n, for running-in
// n + a N_r (exp(-n0 / N_r) - exp(-(n0 + n) / N_r)), for incubation
// n - N_i (exp(-n0 / N_i) - exp(-(n0 + n) / N_i)) [cycles]; the wear loop scales the depth of
// one simulated cycle by it
double effective_cycles(const WearLawParams& law, double n0, double n);

}  // namespace kneesim::wear
