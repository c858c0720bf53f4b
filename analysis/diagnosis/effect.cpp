#include "analysis/diagnosis/effect.h"

#include <cmath>

#include "engine/errors.h"

namespace kneesim::diagnosis {
namespace {

const std::vector<EffectInfo>& library() {
  static const std::vector<EffectInfo> lib = {
      {Effect::none, "none",
       "The measurements are consistent with the baseline model within their scatter.",
       "baseline model with its parameters refitted to all data", DataNeed::none, {}},
      {Effect::running_in, "running_in",
       "New UHMWPE surfaces wear faster at first: machining marks and asperities are removed "
       "and the surface layer reorients before a steady state is reached (Hussin 2024: high "
       "rate over the first 50 000 cycles; simulator tests often exclude the first 0.5-1 Mc).",
       "dV/dN = k F S (1 + a exp(-N / N_r))", DataNeed::none,
       {{"running_in_excess", "initial extra wear-rate ratio a [-]", 1e-3, 1e3, 2.0, true,
         {0.5, 5.0}, false, 0.0},
        {"running_in_cycles", "running-in decay constant N_r [cycles]", 1e3, 3e5, 15000.0, true,
         {4000.0, 50000.0}, true}}},
      {Effect::pressure_dependent_wear, "pressure_dependent_wear",
       "UHMWPE's wear factor falls as the nominal contact pressure rises (Mazzucco & Spector "
       "2003); Abdelgaied 2011 proposed wear proportional to contact area instead of load, "
       "which is the exponent alpha = 1.",
       "dV/dN = k (p / p_ref)^-alpha F S, p = mean contact pressure of the worn geometry",
       DataNeed::two_loads,
       {{"pressure_exponent", "exponent alpha of k ~ p^-alpha [-]", -3.0, 4.0, 0.5, false,
         {1.5}, false, 0.0}}},
      {Effect::cross_shear, "cross_shear",
       "UHMWPE wears far more under multidirectional sliding than under linear tracking: "
       "sliding across the principal molecular orientation breaks the oriented fibrils; k rises "
       "steeply with the cross-shear ratio, up to an order of magnitude (Wang 2001; Kang 2008).",
       "k = k_linear (1 + g CS), CS = cross-shear ratio of the local sliding path",
       DataNeed::kinematic_conditions,
       {{"cross_shear_gain", "gain g of k on the cross-shear ratio [-]", 0.0, 50.0, 3.0, false,
         {}, true, 0.0}}},
      {Effect::creep, "creep",
       "Early penetration of UHMWPE is largely viscoelastic-plastic creep, not wear: depth "
       "grows without volume loss and saturates in time (Zhao 2008), so a wear-only model "
       "over-predicts depth from volume or under-predicts it from k.",
       "depth = scar depth + phi delta_el (1 - exp(-t / tau)), volume unchanged",
       DataNeed::depth_and_volume,
       {{"creep_ratio", "saturated creep over elastic penetration phi [-]", 1e-3, 20.0, 0.5,
         true, {2.0}, false, 0.0},
        {"creep_time_s", "creep time constant tau [s]", 60.0, 1e6, 3600.0, true,
         {600.0, 20000.0}, true}}},
      {Effect::incubation, "incubation",
       "Steady wear of UHMWPE needs an incubation period: the surface must accumulate plastic "
       "strain (ratcheting, orientation) before debris detaches, and early gravimetric wear is "
       "masked by fluid uptake where the soak control does not remove it fully; the measured "
       "volume then lags the steady-state line by an amount proportional to the load "
       "(incubation) or independent of it (uptake). The law here is the load-proportional one: "
       "the wear rate rises from zero to the steady rate with time constant N_i.",
       "dV/dN = k F S (1 - exp(-N / N_i)); V lags k F S N by k F S N_i after a few N_i",
       DataNeed::none,
       {{"incubation_cycles", "incubation time constant N_i [cycles]", 1e2, 5e5, 20000.0, true,
         {3000.0, 100000.0}, true, 0.0}}},
      {Effect::friction, "friction",
       "Force-controlled kinematics follow the friction at the articulation and the rig's "
       "restraint; a friction coefficient different from the assumed one changes AP and IE "
       "motion, and wear follows the kinematics (Dreyer 2023).",
       "mu replaced by a fitted friction coefficient (kinematics and Sarkar factor)",
       DataNeed::kinematics,
       {{"friction_coefficient", "friction coefficient mu [-]", 0.0, 0.5, 0.07, false,
         {0.02, 0.15}, true, 0.07}}},
      {Effect::restraint, "restraint",
       "Force-controlled models miss the kinematics of the rig or the patient because the "
       "restraint they assume is not the one acting: the simulator's springs, or a patient's "
       "ligaments and capsule, are stiffer or softer and engage after a different laxity gap "
       "(Dreyer 2023); AP and IE follow the balance of the applied loads, the conformity of "
       "the insert and this restraint.",
       "restraint springs k_ant, k_post, k_inside, k_IE scaled by s; AP laxity gap g",
       DataNeed::kinematics,
       {{"restraint_stiffness_scale", "scale s of every restraint stiffness [-]", 0.05, 20.0,
         1.0, true, {0.3, 3.0}, false, 1.0},
        {"restraint_gap_mm", "AP laxity gap g of the restraint springs [mm]", 0.0, 10.0, 3.0,
         false, {}, true, 3.0}}},
      {Effect::load_convention, "load_convention",
       "A force-controlled model moves as its loads drive it: an AP force or IE torque applied "
       "with the opposite sign (published work disagrees on the ISO 14243 directions, Wang "
       "2018; a frame turned between the load file and the rig), at another magnitude, or "
       "out of phase with the flexion it is combined with (a load pattern from another gait "
       "than the measured one) moves the tibia the wrong way or at the wrong time. A wrong "
       "sign is the first thing to rule out.",
       "AP force x s_AP delayed by d_AP; IE torque x s_IE delayed by d_IE (signs included)",
       DataNeed::kinematics,
       {{"ap_force_scale", "factor on the AP force waveform, sign included [-]", -3.0, 3.0, 1.0,
         false, {-1.0}, false, 1.0},
        {"ap_force_shift_pct", "delay of the AP force waveform [% of the cycle]", -25.0, 25.0,
         0.0, false, {}, false, 0.0},
        {"ie_torque_scale", "factor on the IE torque waveform, sign included [-]", -3.0, 3.0,
         1.0, false, {}, false, 1.0},
        {"ie_torque_shift_pct", "delay of the IE torque waveform [% of the cycle]", -25.0, 25.0,
         0.0, false, {}, false, 0.0}}},
      {Effect::load_line, "load_line",
       "The medial-lateral split follows where the resultant load line crosses the tibia: a "
       "wear rig fixes it by a medial offset of its axis, while in the patient the limb's "
       "frontal-plane alignment and the adduction moment put it elsewhere; a constant shift "
       "of the line moves a varus-valgus moment proportional to the axial force onto the "
       "tibia.",
       "tibial VV torque = d x axial force (load line moved medially by d)",
       DataNeed::compartment_forces,
       {{"load_line_shift_mm", "medial shift d of the axial load line [mm]", -15.0, 15.0, 0.0,
         false, {-5.0, 5.0}, false, 0.0}}},
      {Effect::vv_moment, "vv_moment",
       "In walking the external knee adduction moment (the ground reaction passing medial to "
       "the knee) loads the medial compartment with its own time course: two stance peaks, "
       "nothing in swing; its lever changes through stance, so the load line does not stay "
       "where a wear rig fixes it.",
       "tibial VV torque = A x stance shape x axial force (a load-line shift following the "
       "stance phase: 0 at heel strike, peaks at 15 % and 47 %, 0 from 62 %)",
       DataNeed::compartment_forces,
       {{"vv_stance_arm_mm", "amplitude A of the stance load-line shift (+ medial) [mm]", -15.0,
         15.0, 0.0, false, {-5.0, 5.0}, false, 0.0}}},
      {Effect::vv_alignment, "vv_alignment",
       "A femoral component implanted or mounted in varus or valgus tilts the condyles in "
       "the frontal plane, so one condyle meets the insert first and carries more of the "
       "load.",
       "femoral component VV angle a (locked femoral VV)", DataNeed::compartment_forces,
       {{"femur_vv_deg", "femoral component VV alignment a (+ varus) [deg]", -5.0, 5.0, 0.0,
         false, {-2.0, 2.0}, false, 0.0}}},
  };
  return lib;
}

}  // namespace

const EffectInfo& effect_info(Effect effect) {
  for (const auto& e : library()) {
    if (e.effect == effect) return e;
  }
  return library().front();
}

const std::vector<Effect>& all_effects() {
  static const std::vector<Effect> all = {Effect::none,        Effect::running_in,
                                          Effect::pressure_dependent_wear,
                                          Effect::cross_shear, Effect::creep,
                                          Effect::incubation, Effect::friction,
                                          Effect::restraint, Effect::load_convention};
  return all;
}

std::string_view effect_name(Effect effect) { return effect_info(effect).name; }

Effect parse_effect(const std::string& name, const std::string& source) {
  std::string allowed;
  for (const auto& e : library()) {
    if (name == e.name) return e.effect;
    allowed += (allowed.empty() ? "" : ", ") + std::string(e.name);
  }
  throw InputError(source + ": effect '" + name + "' is unknown; allowed: " + allowed + ".");
}

double cross_shear_wear_factor(double cross_shear_ratio, double gain) {
  return 1.0 + gain * cross_shear_ratio;
}

double friction_wear_factor(double friction) { return std::sqrt(1.0 + 3.0 * friction * friction); }

}  // namespace kneesim::diagnosis
