// Rough surfaces for the particle model: generated (Gaussian or non-Gaussian, periodic) or
// imported from a measured height map.
//
// Generation follows Hu & Tonder (1992): white noise filtered in the frequency domain by the
// square root of the power spectrum of an exponential autocorrelation
// R(tx, ty) = Rq^2 exp(-2.3 sqrt((tx/bx)^2 + (ty/by)^2)) (bx, by: lengths where R falls to 10 %).
// Skewness and kurtosis are then imposed by a rank-preserving Fleishman power transform
// Y = -c + bZ + cZ^2 + dZ^3 of the filtered Gaussian field, whose targets are corrected until
// the sample moments match. Rejected: Hu & Tonder's Johnson translator applied to the noise
// before filtering, which needs a separate system fit per target and hits the moments only
// through the filter's moment relations (a few per cent off on finite grids).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "wear/particles/grid.h"

namespace kneesim::particles {

struct SurfaceSpec {
  double rq = 0.0;                 // root-mean-square roughness [m]
  double skewness = 0.0;           // [-]
  double kurtosis = 3.0;           // [-] (3 = Gaussian)
  double correlation_length = 0.0; // 10 % autocorrelation length, both directions [m]
  std::uint64_t seed = 1;          // random seed [-]
};

struct SurfaceStats {
  double mean = 0.0;      // [m]
  double rq = 0.0;        // [m]
  double skewness = 0.0;  // [-]
  double kurtosis = 0.0;  // [-]
};

// heights (grid.size(), [m], zero mean) of a surface periodic in both directions; throws
// InputError naming `source` for Rq or correlation length <= 0 or moments that no Fleishman
// transform reaches (kurtosis below 1 + skewness^2 or far beyond it)
std::vector<double> make_rough_surface(const Grid& grid, const SurfaceSpec& spec,
                                       const std::string& source);

SurfaceStats calc_surface_stats(const std::vector<double>& heights);

// coefficients (b, c, d) of the Fleishman transform for a target skewness and kurtosis;
// returns false when Newton's method finds none
bool solve_fleishman(double skewness, double kurtosis, double& b, double& c, double& d);

}  // namespace kneesim::particles
