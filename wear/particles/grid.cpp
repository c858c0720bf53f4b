#include "wear/particles/grid.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "engine/errors.h"

namespace kneesim::particles {

double memory_budget_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0.0;
  std::string unit;
  while (in >> key >> kb >> unit) {
    if (key == "MemTotal:") return 0.5 * kb * 1024.0;
  }
  return 4.0 * 1024.0 * 1024.0 * 1024.0;
}

double estimate_memory_bytes(const Grid& grid, int nz) {
  // padded real and complex buffers of the contact solver (about 12 padded fields) plus the
  // stress levels (6 spectra, 6 components, the von Mises field and its refinement)
  const double padded = 4.0 * grid.nx * grid.ny;
  const double contact = 12.0 * padded * 16.0;
  const double stress = 12.0 * padded * 16.0 + 3.0 * nz * double(grid.nx) * grid.ny * 8.0;
  return contact + stress;
}

void check_grid(const Grid& grid, int nz, const std::string& source) {
  auto fail = [&](const std::string& what) { throw InputError(source + ": " + what); };
  char buf[256];
  if (grid.nx <= 0 || grid.ny <= 0 || grid.nx % 2 != 0 || grid.ny % 2 != 0) {
    std::snprintf(buf, sizeof buf,
                  "grid size %d x %d is not allowed; both sizes must be positive even integers",
                  grid.nx, grid.ny);
    fail(buf);
  }
  if (!(grid.dx > 0.0) || !(grid.dy > 0.0) || !std::isfinite(grid.dx) ||
      !std::isfinite(grid.dy)) {
    std::snprintf(buf, sizeof buf,
                  "grid spacing %g x %g nm is not allowed; the spacing must be > 0",
                  grid.dx * 1e9, grid.dy * 1e9);
    fail(buf);
  }
  if (nz <= 0) {
    std::snprintf(buf, sizeof buf, "depth levels nz = %d is not allowed; nz must be > 0", nz);
    fail(buf);
  }
  const double need = estimate_memory_bytes(grid, nz);
  const double budget = memory_budget_bytes();
  if (!(need <= budget)) {
    std::snprintf(buf, sizeof buf,
                  "grid %d x %d x %d needs about %.1f GB, more than the %.1f GB allowed (half "
                  "the machine's memory); use a smaller grid",
                  grid.nx, grid.ny, nz, need / 1e9, budget / 1e9);
    fail(buf);
  }
}

}  // namespace kneesim::particles
