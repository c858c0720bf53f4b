// Normal contact of rough surfaces: the conjugate-gradient method of Polonsky & Keer (Wear
// 231:206, 1999) with the total load imposed, extended by a hardness cap p <= H (points at
// the cap leave the CG set and may interpenetrate, i.e. they flow plastically). Deflection
// products u = K * p go through DeflectionOperator (DC-FFT), two per iteration.
//
// Sums over the grid (load, CG inner products) are taken row by row and then over rows in
// index order, so results are bit-identical for any OpenMP thread count.
#pragma once

#include <string>
#include <vector>

#include "wear/particles/deflection.h"

namespace kneesim::particles {

struct ContactOptions {
  double load = 0.0;          // total normal load on the grid [N]
  double hardness = 0.0;      // pressure cap H of the softer body; <= 0 for none [Pa]
  double tolerance = 1e-8;    // relative pressure change that ends the iterations [-]
  int max_iterations = 2000;  // [-]
};

struct ContactResult {
  std::vector<double> pressure;    // p per cell, grid.size() [Pa]
  std::vector<double> deflection;  // u = K * p per cell, grid.size() [m]
  std::vector<double> gap;         // deformed gap h + u - approach, grid.size() [m]
  double approach = 0.0;           // rigid-body approach [m]
  double load = 0.0;               // sum p dA [N]
  double contact_fraction = 0.0;   // share of cells with p > 0 [-]
  double capped_fraction = 0.0;    // share of cells at p = H [-]
  int iterations = 0;              // CG iterations [-]
  bool converged = false;          // tolerance reached [-]
};

// Solves for the pressure that closes the gap `h` (initial separation per cell, grid.size(),
// [m]) under the total load; `p_start` (grid.size(), optional) warm-starts the iterations.
ContactResult solve_contact(const DeflectionOperator& op, const std::vector<double>& h,
                            const ContactOptions& options,
                            const std::vector<double>* p_start = nullptr);

// Throws InputError naming `source` when the load cannot be carried: not positive, or above
// hardness x grid area.
void check_load(double load, double hardness, const Grid& grid, const std::string& source);

// Sum of v over the grid in a fixed order (rows, then over rows), for any thread count.
double ordered_sum(const std::vector<double>& v, int nx, int ny);

}  // namespace kneesim::particles
