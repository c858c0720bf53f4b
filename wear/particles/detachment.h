// Particle criterion (the particle-size study): a 3D connected region of the softer body
// where the von Mises stress exceeds its yield stress, and that reaches the surface, detaches
// as one particle. Regions are 6-connected voxels of the refined depth grid; across the
// sliding direction the grid may be periodic, in which case a region is followed across the
// seam (its width is measured unwrapped). Regions that stay below the surface are plastic
// zones, not particles.
#pragma once

#include <functional>
#include <vector>

#include "wear/particles/grid.h"

namespace kneesim::particles {

struct Particle {
  double volume = 0.0;     // [m^3]
  double eq_radius = 0.0;  // (3 V / 4 pi)^(1/3) [m]
  double length = 0.0;     // extent along the sliding direction x [m]
  double width = 0.0;      // extent across it, y [m]
  double thickness = 0.0;  // depth from the surface [m]
  double x = 0.0, y = 0.0; // centroid of its surface cells [m]
};

struct Detachment {
  std::vector<Particle> particles;     // in scan order of their first surface voxel
  std::vector<double> removed_depth;   // per surface cell, grid.size() [m]
};

// particles from a von Mises field on nz voxel levels of thickness dz (voxel l spans depths
// l dz .. (l + 1) dz)
Detachment find_particles(const std::vector<double>& von_mises, const Grid& grid, int nz,
                          double dz, double yield_stress);

// particles from a field computed level by level from the surface down: level(k, out) writes
// depth level z_k = k dz (grid.size() values, compared with `threshold`). The levels stop at
// the first one below the surface with no value above the threshold (a surface-reaching
// region cannot pass through it), at most nz, and are refined `refine` times by linear
// interpolation before labelling. `levels` is scratch for nz x grid.size() values;
// *computed gets the number of levels computed.
Detachment find_particles_from_levels(const std::function<void(int, double*)>& level,
                                      const Grid& grid, int nz, double dz, int refine,
                                      double threshold, std::vector<double>& levels,
                                      int* computed = nullptr);

}  // namespace kneesim::particles
