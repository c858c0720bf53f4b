// The kinetic/internal energy ratio of a simulated cycle of the solid: the quasi-static
// validity measure of a mass-scaled run (issue 11: below 5 %). A pure kernel shared by
// `kneesim run` (analysis/run/solid_outputs.h) and the wear loop (wear/wear_loop.h).
#pragma once

#include <algorithm>
#include <vector>

namespace kneesim::engine::solid {

struct EnergyRatio {
  double max = 0.0;    // largest kinetic/internal ratio over the steps whose internal energy is
                       // at least a tenth of the cycle's largest (swing, nearly unloaded, is
                       // left out) [-]
  double cycle = 0.0;  // sum of the kinetic over the sum of the internal energy [-]
  // `max` over the steps after the first settling_steps: a run that starts from rest puts the
  // femur on the undeformed insert at first touch under the t = 0 load, and its settling (a
  // few ms) is a transient of the start, not of the gait cycle; on a stiff insert, whose
  // internal energy is small, it can dominate `max` (DM implant, CFR-PEEK: 58 % within the
  // first 0.3 % of the cycle, 0.6 % after it) [-]
  double max_after_settling = 0.0;
};

// kinetic [J] and internal energy (elastic + hourglass + plastic work) [J] per step;
// settling_steps: the steps of the start's settling, left out of max_after_settling
inline EnergyRatio calc_energy_ratio(const std::vector<double>& kinetic,
                                     const std::vector<double>& internal,
                                     size_t settling_steps = 0) {
  double internal_max = 0.0, kinetic_sum = 0.0, internal_sum = 0.0;
  EnergyRatio r;
  for (double u : internal) internal_max = std::max(internal_max, u);
  for (size_t i = 0; i < internal.size() && i < kinetic.size(); ++i) {
    kinetic_sum += kinetic[i];
    internal_sum += internal[i];
    if (internal[i] >= 0.1 * internal_max && internal[i] > 0.0) {
      r.max = std::max(r.max, kinetic[i] / internal[i]);
      if (i >= settling_steps) r.max_after_settling = std::max(r.max_after_settling, kinetic[i] / internal[i]);
    }
  }
  r.cycle = internal_sum > 0.0 ? kinetic_sum / internal_sum : 0.0;
  return r;
}

}  // namespace kneesim::engine::solid
