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

// elastic-foundation pressure [Pa] for penetration d [m] of a layer of thickness h [m];
// the nonlinear law is capped just short of d = h (its log singularity) — a penetration that
// deep is reported as runaway long before it is reached
inline double ef_pressure(ContactLaw law, double K, double d, double h) {
  if (d <= 0.0) return 0.0;
  switch (law) {
    case ContactLaw::kLinear:
      return K * d / h;
    case ContactLaw::kNonlinear:
      return -K * std::log(1.0 - std::min(d / h, 0.99));
  }
  return 0.0;
}

// dp/dd [Pa/m], the tangent stiffness per unit area
inline double ef_stiffness(ContactLaw law, double K, double d, double h) {
  switch (law) {
    case ContactLaw::kLinear:
      return K / h;
    case ContactLaw::kNonlinear:
      return K / (h - std::min(std::max(d, 0.0), 0.99 * h));
  }
  return 0.0;
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
