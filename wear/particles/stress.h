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
#include <numbers>
#include <vector>

#include "wear/particles/fft.h"
#include "wear/particles/grid.h"

namespace kneesim::particles {

enum class StressComponent { kXX = 0, kYY, kZZ, kXY, kXZ, kYZ };

// The FFT side shared by the homogeneous and the layered stress fields: the pressure spectrum
// on the zero-padded grid (normalised for the inverse), six stress spectra that a depth level
// fills with its frequency responses, and the way back to the grid (inverse FFT, unpadded
// part) with the von Mises stress from there.
class StressSpectra {
 public:
  explicit StressSpectra(const Grid& grid);

  void set_pressure(const std::vector<double>& pressure);
  const Complex& pressure(long k) const { return p_hat_[k]; }
  // stress spectra at frequency k, StressComponent order (scratch: one level at a time)
  void set(long k, const std::array<Complex, 6>& stress) const {
    for (int c = 0; c < 6; ++c) spec_[c][k] = stress[c];
  }
  // Sets the stress spectra of one level, frequency by frequency (rows in parallel): the
  // Nyquist lines are dropped (odd responses cannot be represented there), the mean gets
  // mean(P) and every other frequency wave(fx, iy, kx, ky, P), with P the pressure spectrum
  // there, fx the signed x and iy the y frequency index and kx, ky the wavenumbers [1/m];
  // each returns the six stress spectra in StressComponent order.
  template <class Mean, class Wave>
  void fill(const Mean& mean, const Wave& wave) const {
    const int npx = npx_, npy = npy_, nc = nyc();
#pragma omp parallel for schedule(static)
    for (int ix = 0; ix < npx; ++ix) {
      const int fx = ix <= npx / 2 ? ix : ix - npx;
      const double kx = 2.0 * std::numbers::pi * fx / (npx * grid_.dx);
      for (int iy = 0; iy < nc; ++iy) {
        const long k = static_cast<long>(ix) * nc + iy;
        const double ky = 2.0 * std::numbers::pi * iy / (npy * grid_.dy);
        const Complex& P = p_hat_[k];
        if (ix == npx / 2 || iy == npy / 2) {
          set(k, {});
        } else if (ix == 0 && iy == 0) {
          set(k, mean(P));
        } else {
          set(k, wave(fx, iy, kx, ky, P));
        }
      }
    }
  }
  // the six components of the spectra set, each grid.size() [Pa]
  void to_grid(std::array<std::vector<double>, 6>& out) const;
  // the von Mises stress of the spectra set, grid.size() [Pa]
  void to_von_mises(double* vm) const;

  const Grid& grid() const { return grid_; }
  int npx() const { return npx_; }
  int npy() const { return npy_; }
  int nyc() const { return fft_.nyc(); }

 private:
  Grid grid_;
  int npx_, npy_;
  Fft2 fft_;
  std::vector<Complex> p_hat_;                       // padded pressure spectrum
  mutable std::array<std::vector<Complex>, 6> spec_; // stress spectra of one level
  mutable std::vector<double> real_;                 // scratch padded field
  mutable std::array<std::vector<double>, 6> comp_;  // scratch components
};

// the stresses of a plane wave along e1 = (c, s) (components 11, 22, 33, 12, 13, 23 in the
// wave's frame) rotated to x, y, in StressComponent order
std::array<Complex, 6> rotate_plane_wave(double c, double s, Complex s11, Complex s22,
                                         Complex s33, Complex s12, Complex s13, Complex s23);

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

  const Grid& grid() const { return spectra_.grid(); }

 private:
  // fills the spectra with the responses at depth z
  void fill_spectra(double z) const;

  double nu_;
  double mu_ = 0.0;
  StressSpectra spectra_;
};

// von Mises stress of a stress state [Pa]
double von_mises(double sxx, double syy, double szz, double sxy, double sxz, double syz);

// von Mises field on nz levels z_k = k dz (k = 0 .. nz-1), level-major (k * grid.size() + cell),
// of a SubsurfaceStress or a LayeredSubsurfaceStress
template <class Stress>
std::vector<double> calc_von_mises_field(const Stress& stress, int nz, double dz) {
  const long n = stress.grid().size();
  std::vector<double> vm(static_cast<long>(nz) * n);
  for (int k = 0; k < nz; ++k) stress.calc_von_mises(k * dz, vm.data() + k * n);
  return vm;
}

// vertical refinement by linear interpolation: `factor` voxels per level interval, voxel l
// centred at depth (l + 0.5) dz / factor; returns (nz - 1) * factor levels
std::vector<double> refine_levels(const std::vector<double>& coarse, long cells, int nz,
                                  int factor);

}  // namespace kneesim::particles
