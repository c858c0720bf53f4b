// Archard wear with the Sarkar correction (physics.md section 6): pure kernels.
//
//   dh = k p ds sqrt(1 + 3 mu^2)
//
// k in m^2/N (1 mm^3/(N mm) = 1 mm^2/N = 1e-6 m^2/N), p in Pa, ds in m.
// The Sarkar factor accounts for the frictional shear adding to the normal load in the
// material's yield (von Mises with tau = mu p).
#pragma once

#include <cmath>

namespace kneesim::wear {

// converts a wear factor in mm^3/(N mm) (= mm^2/N) to SI m^2/N
inline constexpr double kWearFactorSI = 1e-6;

inline double sarkar_factor(double mu) { return std::sqrt(1.0 + 3.0 * mu * mu); }

// linear wear depth [m] for wear factor k [m^2/N], pressure p [Pa], slip ds [m], friction mu
inline double archard_increment(double k, double p, double ds, double mu) {
  return k * p * ds * sarkar_factor(mu);
}

}  // namespace kneesim::wear
