// Subsurface stresses of a half-space under surface pressure p and friction traction s = mu p
// (along +x), by FFT convolution with the normal and tangential influence functions written
// in the frequency domain (closed-form frequency responses of the Boussinesq and Cerruti
// problems, derived for a plane wave and rotated to its direction; cf. Liu & Wang, Wear 2002).
// The tractions are zero-padded to twice the grid along x (and along y unless the grid is
// periodic there), so the images of the FFT's periodic sum sit a whole grid length away.
//
// Why frequency responses and not the spatial rectangle-element coefficients (as for the
// deflection): the stress at every depth level then costs one exponential per frequency and
// six inverse FFTs, with no per-level kernel transforms; a 256 x 256 x 64 von Mises field
// fits in the time of a few hundred FFTs. The price is the band-limited (sinc) reading of the
// pressure cells, which matters only within a cell of the surface.
#pragma once

#include <array>
#include <vector>

#include "wear/particles/fft.h"
#include "wear/particles/grid.h"

namespace kneesim::particles {

enum class StressComponent { kXX = 0, kYY, kZZ, kXY, kXZ, kYZ };

class SubsurfaceStress {
 public:
  SubsurfaceStress(const Grid& grid, double poisson_ratio);

  // surface tractions: pressure p (grid.size(), [Pa]) and friction coefficient mu [-]
  void set_traction(const std::vector<double>& pressure, double friction);
  // the six stress components at depth z [m], each grid.size(), tension positive [Pa]
  // (not thread-safe: uses internal scratch)
  void calc_stress(double z, std::array<std::vector<double>, 6>& out) const;
  // the von Mises stress at depth z into vm (grid.size()) [Pa]
  void calc_von_mises(double z, double* vm) const;

  const Grid& grid() const { return grid_; }

 private:
  Grid grid_;
  double nu_;
  double mu_ = 0.0;
  int npx_, npy_;
  Fft2 fft_;
  std::vector<Complex> p_hat_;                       // padded pressure spectrum
  mutable std::array<std::vector<Complex>, 6> spec_; // scratch spectra
  mutable std::vector<double> real_;                 // scratch padded field
  mutable std::array<std::vector<double>, 6> comp_;  // scratch components
};

// von Mises stress of a stress state [Pa]
double von_mises(double sxx, double syy, double szz, double sxy, double sxz, double syz);

// von Mises field on nz levels z_k = k dz (k = 0 .. nz-1), level-major (k * grid.size() + cell)
std::vector<double> calc_von_mises_field(const SubsurfaceStress& stress, int nz, double dz);

// vertical refinement by linear interpolation: `factor` voxels per level interval, voxel l
// centred at depth (l + 0.5) dz / factor; returns (nz - 1) * factor levels
std::vector<double> refine_levels(const std::vector<double>& coarse, long cells, int nz,
                                  int factor);

}  // namespace kneesim::particles
