#include "engine/solid/solid_material.h"

#include <algorithm>
#include <cmath>

namespace kneesim::engine::solid {

StressUpdate calc_stress(const SolidMaterial& m, const Sym6& strain, const Sym6& plastic_strain,
                         double alpha) {
  const double lambda = m.lame_lambda(), mu = m.shear_modulus();
  const Sym6 e = strain - plastic_strain;
  const double tr = e[0] + e[1] + e[2];
  StressUpdate out;
  out.stress = 2.0 * mu * e;
  for (int i = 0; i < 3; ++i) out.stress[i] += lambda * tr;
  out.plastic_strain = plastic_strain;
  out.alpha = alpha;
  if (m.kind == SolidMaterialKind::kElastic) return out;

  // trial deviator and its norm (tensor norm: off-diagonals count twice)
  const double p = (out.stress[0] + out.stress[1] + out.stress[2]) / 3.0;
  Sym6 dev = out.stress;
  for (int i = 0; i < 3; ++i) dev[i] -= p;
  const double norm = std::sqrt(dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2] +
                                2.0 * (dev[3] * dev[3] + dev[4] * dev[4] + dev[5] * dev[5]));
  const double k23 = std::sqrt(2.0 / 3.0);
  const double f = norm - k23 * calc_yield_stress(m, alpha);
  if (f <= 0.0) return out;

  // radial return (Simo & Hughes box 3.2): the hardening branch first; if it overshoots the
  // cap, the solution lies on the flat branch where only the elastic shear relaxes
  double dgamma = f / (2.0 * mu + (2.0 / 3.0) * m.hardening_modulus);
  const bool capped = m.yield_cap > m.yield_stress;
  if (capped && m.yield_stress + m.hardening_modulus * (alpha + k23 * dgamma) > m.yield_cap) {
    dgamma = (norm - k23 * m.yield_cap) / (2.0 * mu);
  }
  const Sym6 n = dev / norm;
  out.stress -= 2.0 * mu * dgamma * n;
  out.plastic_strain += dgamma * n;
  out.alpha = alpha + k23 * dgamma;
  // dissipation: the updated deviator's norm times the plastic increment
  out.plastic_work = (norm - 2.0 * mu * dgamma) * dgamma;
  return out;
}

double calc_von_mises(const Sym6& s) {
  const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

}  // namespace kneesim::engine::solid
