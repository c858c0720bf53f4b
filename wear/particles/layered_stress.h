// Subsurface stresses of a layered body: an elastic film of thickness t bonded to an elastic
// substrate half-space, under surface pressure p and friction traction s = mu p (along +x).
// Same grid, padding, FFT and sign conventions as SubsurfaceStress (stress.h), of which this
// is the layered counterpart.
//
// Each wave vector k is a plane wave along e1 = k / |k|; its load splits into plane strain in
// (e1, z) (pressure P and in-plane shear Q1 = c Q) and antiplane shear along e2 (Q2 = -s Q).
// Plane strain has two decaying and two growing solutions (a + b z) exp(-+alpha z) in the film
// and two decaying ones in the substrate: six coefficients fixed by the surface tractions and the
// continuity of u1, u3, sigma_33, sigma_13 at z = t (as in layered_compliance_frf of
// deflection.cpp, with the growing solutions referenced at z = t so nothing overflows).
// Antiplane shear has a closed form. The solutions depend on |k| only, so the constructor
// solves the 6x6 system once per (|kx|, ky) and stores 16 numbers (13 MB for a 320 x 320
// grid); a depth level then costs one exponential per frequency and six inverse FFTs, as for
// the homogeneous body (measured at 256 x 256: 15 % slower in the film, 4 % below it). Beyond
// alpha t = 40 the substrate is invisible (exp(-40)) and the film's half-space solution is
// used.
//
// The zero wavenumber (the mean traction) has no plane-wave direction; SubsurfaceStress uses
// the direction average of the alpha -> 0 limit, sigma_xx = sigma_yy = -(1 + 2 nu)/2 P. Its
// layered counterpart here: sigma_zz = -P and sigma_xz = -Q throughout, and one equibiaxial
// in-plane strain e shared by film and substrate (they are bonded), each layer then carrying
// (E e - nu P) / (1 - nu). The strain e is the direction-averaged surface strain of the
// plane-wave solution averaged over the central frequency cell of the padded grid: a film
// thin against the grid window gets the substrate's strain (the alpha -> 0 limit, film
// stresses set by the substrate's lateral contraction), a film thick against it its own
// half-space value, and a homogeneous body gives -(1 + 2 nu)/2 P (to rounding). Rejected:
// each layer's own lateral constraint (-nu/(1 - nu) P, the uniaxial strain of a uniform load),
// which disagrees with SubsurfaceStress in the homogeneous limit, and the strict alpha -> 0
// limit alone, which misses the film half-space for films thicker than the window.
#pragma once

#include <array>
#include <vector>

#include "wear/particles/fft.h"
#include "wear/particles/grid.h"
#include "wear/particles/stress.h"

namespace kneesim::particles {

class LayeredSubsurfaceStress {
 public:
  // film thickness t > 0 [m], moduli E > 0 [Pa], Poisson ratios in [0, 0.5) [-]
  LayeredSubsurfaceStress(const Grid& grid, double film_thickness, double film_modulus,
                          double film_poisson, double substrate_modulus,
                          double substrate_poisson);

  // surface tractions: pressure p (grid.size(), [Pa]) and friction coefficient mu [-]
  void set_traction(const std::vector<double>& pressure, double friction);
  // the six stress components (StressComponent order) at depth z >= 0 [m], each grid.size(),
  // tension positive [Pa]; z < t lies in the film, z >= t in the substrate
  // (not thread-safe: uses internal scratch)
  void calc_stress(double z, std::array<std::vector<double>, 6>& out) const;
  // the von Mises stress at depth z into vm (grid.size()) [Pa]
  void calc_von_mises(double z, double* vm) const;

  const Grid& grid() const { return spectra_.grid(); }

 private:
  // fills the spectra with the responses at depth z
  void fill_spectra(double z) const;

  double t_;                 // film thickness [m]
  double nu_f_, nu_s_;       // Poisson ratios [-]
  double mean_xx_f_;         // zero-wavenumber sigma_xx = sigma_yy per unit P in the film [-]
  double mean_xx_s_;         // the same in the substrate [-]
  double mu_ = 0.0;
  StressSpectra spectra_;
  std::vector<double> coef_;  // per (|kx|, ky): 6 unit P, 6 unit Q1, 3 antiplane, exp(-alpha t)
};

}  // namespace kneesim::particles
