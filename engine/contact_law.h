// Elastic-foundation contact and friction kernels (physics.md section 4). Pure, unit-tested.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "engine/model.h"

namespace kneesim::engine {

// foundation modulus K = (1 - nu) E / ((1 + nu)(1 - 2 nu)) [Pa]
inline double foundation_modulus(double youngs_modulus, double poisson) {
  return (1.0 - poisson) * youngs_modulus / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
}

// The elastic-foundation law p = K g^n of a layer of thickness h [m] at penetration d [m], with
// the strain measure g = d/h (linear) or -ln(1 - d/h) (nonlinear; capped just short of d = h,
// its log singularity: a penetration that deep is reported as runaway long before it is
// reached). n = 1 is physics.md's pair of laws. The calibration against the deformable insert
// fits n with K: over a paraboloidal overclosure a pointwise law p ~ d^n gives a patch whose
// peak pressure is n + 1 times its mean (2 for n = 1, 1.5 for n = 1/2, Hertz's ratio), and the
// deformable insert's patches are flatter than the linear law's. An exponent below 1 runs
// linear in g below g = kExponentLinearStrain (the same pressure there), so that the tangent
// stays finite at first touch.
inline constexpr double kExponentLinearStrain = 1e-4;

// the law's strain measure g(d) and dg/dd [1/m]
inline double ef_strain(ContactLaw law, double d, double h) {
  return law == ContactLaw::kLinear ? d / h : -std::log(1.0 - std::min(d / h, 0.99));
}
inline double ef_strain_rate(ContactLaw law, double d, double h) {
  return law == ContactLaw::kLinear ? 1.0 / h : 1.0 / (h - std::min(std::max(d, 0.0), 0.99 * h));
}

// pressure [Pa] at strain g of the law p = K g^n (the linear run-in below
// kExponentLinearStrain for n < 1)
inline double ef_pressure_at_strain(double K, double n, double g) {
  if (n < 1.0 && g < kExponentLinearStrain) {
    return K * std::pow(kExponentLinearStrain, n - 1.0) * g;
  }
  return K * std::pow(g, n);
}

// dp/dg [Pa] at strain g
inline double ef_pressure_slope(double K, double n, double g) {
  if (n < 1.0 && g < kExponentLinearStrain) return K * std::pow(kExponentLinearStrain, n - 1.0);
  return K * n * std::pow(g, n - 1.0);
}

// elastic-foundation pressure [Pa] for penetration d [m] of a layer of thickness h [m]; n = 1
// evaluates physics.md's expressions as written (bit for bit the laws without an exponent)
inline double ef_pressure(ContactLaw law, double K, double n, double d, double h) {
  if (d <= 0.0) return 0.0;
  if (n != 1.0) return ef_pressure_at_strain(K, n, ef_strain(law, d, h));
  switch (law) {
    case ContactLaw::kLinear:
      return K * d / h;
    case ContactLaw::kNonlinear:
      return -K * std::log(1.0 - std::min(d / h, 0.99));
  }
  return 0.0;
}

// dp/dd [Pa/m], the tangent stiffness per unit area
inline double ef_stiffness(ContactLaw law, double K, double n, double d, double h) {
  if (n != 1.0) {
    return ef_pressure_slope(K, n, ef_strain(law, std::max(d, 0.0), h)) * ef_strain_rate(law, d, h);
  }
  switch (law) {
    case ContactLaw::kLinear:
      return K / h;
    case ContactLaw::kNonlinear:
      return K / (h - std::min(std::max(d, 0.0), 0.99 * h));
  }
  return 0.0;
}

// pressure [Pa] and tangent stiffness per area [Pa/m] together, for the contact loop: the strain
// g (a log for the nonlinear law) is taken once; the same expressions as ef_pressure and
// ef_stiffness, so the same bits
struct EfPressureStiffness {
  double pressure;
  double stiffness;
};
inline EfPressureStiffness ef_pressure_and_stiffness(ContactLaw law, double K, double n, double d,
                                                     double h) {
  if (d <= 0.0 || n == 1.0) return {ef_pressure(law, K, n, d, h), ef_stiffness(law, K, n, d, h)};
  const double g = ef_strain(law, d, h);
  return {ef_pressure_at_strain(K, n, g), ef_pressure_slope(K, n, g) * ef_strain_rate(law, d, h)};
}

// regularized Coulomb traction [Pa] opposing the tangential slip velocity v_s [m/s]
inline Eigen::Vector3d friction_traction(double mu, double p, const Eigen::Vector3d& v_s,
                                         double eps) {
  return (-mu * p / std::sqrt(v_s.squaredNorm() + eps * eps)) * v_s;
}

// spring-gap law (physics.md section 2): force [N or N m] of a restraint at displacement x
inline double spring_gap_force(const RestraintSpring& s, double x) {
  if (x > s.gap) return -s.k_inside * s.gap - s.k_positive * (x - s.gap);
  if (x < -s.gap) return s.k_inside * s.gap - s.k_negative * (x + s.gap);
  return -s.k_inside * x;
}

// -d spring_gap_force / dx [N/m or N m/rad]
inline double spring_gap_stiffness(const RestraintSpring& s, double x) {
  if (x > s.gap) return s.k_positive;
  if (x < -s.gap) return s.k_negative;
  return s.k_inside;
}

}  // namespace kneesim::engine
