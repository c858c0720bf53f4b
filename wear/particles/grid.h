// The surface grid shared by every particle-model kernel: nx points along the sliding
// direction x, ny across it (y), uniform spacing, fields stored row-major with y fastest
// (index i * ny + j), cell centres at x_i = (i - (nx - 1) / 2) dx.
#pragma once

#include <string>

namespace kneesim::particles {

struct Grid {
  int nx = 0;              // points along the sliding direction [-]
  int ny = 0;              // points across the sliding direction [-]
  double dx = 0.0;         // spacing along x [m]
  double dy = 0.0;         // spacing along y [m]
  bool periodic_y = false; // periodic across the sliding direction (line contact) [-]

  long size() const { return static_cast<long>(nx) * ny; }
  double x(int i) const { return (i - 0.5 * (nx - 1)) * dx; }  // cell centre [m]
  double y(int j) const { return (j - 0.5 * (ny - 1)) * dy; }  // cell centre [m]
  double cell_area() const { return dx * dy; }                 // [m^2]
};

// Largest number of bytes a particle run may plan to allocate (half the machine's memory,
// read from /proc/meminfo, or 4 GiB when unknown).
double memory_budget_bytes();

// Throws InputError naming `source` when the grid is unusable: sizes not positive, not even
// (the real FFT needs even sizes), spacing <= 0, or an estimated working memory of the BEM
// (padded FFT buffers plus nz stress levels) above memory_budget_bytes().
void check_grid(const Grid& grid, int nz, const std::string& source);

// estimated working memory of a contact solve plus an nz-level stress field [bytes]
double estimate_memory_bytes(const Grid& grid, int nz);

}  // namespace kneesim::particles
