// The library of named, physically motivated model extensions the diagnosis chooses from
// (issue 4; physics.md section 6, "what constant-k Archard gets wrong"). Each effect is a real
// extension the forward simulators run with: the block-on-ring laws are in
// wear/bor/bor_wear_law.h; the knee-only kernels (cross-shear, friction) are here so that the
// knee wear and kinematics cases can call them. An effect declares the data it needs, which
// decides whether it is a candidate for a case (a one-directional block-on-ring cannot show
// cross-shear; a volume-only data set cannot show creep).
#pragma once

#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace kneesim::diagnosis {

enum class Effect {
  none,                     // the baseline model is enough
  running_in,               // extra early wear decaying with cycles
  pressure_dependent_wear,  // k = k_ref (p / p_ref)^-alpha (alpha = 1: contact-area law)
  cross_shear,              // k rising with the cross-shear ratio of the sliding path
  creep,                    // penetration without volume loss, decaying in time
  incubation,               // the wear rate rises from zero to the steady rate (early deficit)
  friction,                 // a different friction coefficient, visible in kinematics
  restraint,                // a different soft-tissue restraint (stiffness, gap), in kinematics
  load_convention,          // the applied AP force / IE torque differ in sign, scale or timing
  load_line,                // the axial load line at another mediolateral position
  vv_moment,                // a varus-valgus moment following the gait phase (stance)
  vv_alignment,             // varus-valgus alignment of the femoral component
};

// what an effect needs to be identifiable
enum class DataNeed {
  none,                   // any wear curve
  two_loads,              // wear at two or more contact pressures
  depth_and_volume,       // penetration depth measured besides volume
  kinematic_conditions,   // two or more kinematic conditions (cross-shear ratios)
  kinematics,             // measured kinematics (AP, IE)
  compartment_forces,     // measured medial and lateral contact forces
};

struct ParamSpec {
  std::string name;            // I/O name with unit, e.g. "running_in_cycles"
  std::string description;     // one line for reports
  double lower = 0.0;          // bound, I/O units
  double upper = 0.0;          // bound, I/O units
  double initial = 0.0;        // default start, I/O units
  bool log_scale = false;      // fitted in log space (positive, multiplicative parameters)
  std::vector<double> starts;  // extra starts for multi-start fits, I/O units
  // the lower bound is a physical limit (a laxity gap or a friction coefficient of 0) or the
  // data's resolution limit (a time constant far shorter than the first measurement: every
  // shorter value fits the same), not a search bound: a fit may end there legitimately
  // (diagnose.h, find_params_at_bound); an upper bound is always a search bound
  bool lower_is_limit = false;
  // the value at which the effect vanishes (the baseline model), for a parameter that sets the
  // effect's size (detection.h); NaN for a shape parameter (a time constant, a delay's partner)
  double null_value = std::numeric_limits<double>::quiet_NaN();
};

struct EffectInfo {
  Effect effect;
  std::string_view name;      // snake_case name used in files and on the command line
  std::string_view physics;   // the physical explanation, for reports
  std::string_view extension; // the model extension as a formula, for reports
  DataNeed needs;
  std::vector<ParamSpec> params;  // default parameter specs (a case may narrow them)
};

const EffectInfo& effect_info(Effect effect);
const std::vector<Effect>& all_effects();
std::string_view effect_name(Effect effect);
// throws InputError naming `source` and the allowed names
Effect parse_effect(const std::string& name, const std::string& source);

// knee-wear kernels for the knee cases (the BOR laws live in wear/bor/bor_wear_law.h)
// cross-shear: k(CS) = k_linear (1 + gain CS), CS in [0, 1] the cross-shear ratio [-]
double cross_shear_wear_factor(double cross_shear_ratio, double gain);
// Sarkar-corrected Archard friction factor with a changed friction coefficient [-]
double friction_wear_factor(double friction);

}  // namespace kneesim::diagnosis
