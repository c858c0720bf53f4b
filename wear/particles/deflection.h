// Normal surface deflection of the two contacting bodies by DC-FFT (Liu, Wang & Liu 2000):
// the influence coefficient of a uniformly loaded rectangle (Love 1929, closed form) sampled
// on a grid twice the size of the contact grid, so that the cyclic convolution of the FFT
// equals the linear (non-periodic) one on the contact grid. Across the sliding direction the
// grid may instead be periodic (a long line contact): the influence coefficients are then
// summed over periodic images, with the logarithmically divergent constant of the 1/r kernel
// removed image by image (a constant deflection is absorbed by the rigid approach) and the
// remaining tail beyond the last image added in closed form.
//
// A transfer film of thickness t on one body (the layered model) changes that body's
// compliance from the film's at short wavelengths to the substrate's at long ones; its
// frequency response has no closed-form inverse, so it is split into a homogeneous film
// kernel (Love), a smooth 1/sqrt(r^2 + t^2) far-field term and a remainder that decays
// exponentially in frequency, which alone is sampled in the frequency domain.
//
// Rejected: the frequency response of the half-space sampled directly (periodic images of
// the whole padded domain and an undefined zero mode spoil the far field).
#pragma once

#include <vector>

#include "wear/particles/fft.h"
#include "wear/particles/grid.h"

namespace kneesim::particles {

struct ElasticBody {
  double youngs_modulus = 0.0;  // E [Pa]
  double poisson_ratio = 0.3;   // nu [-]
  double film_thickness = 0.0;  // transfer film on this body; 0 = homogeneous [m]
  double film_modulus = 0.0;    // E of the film [Pa]
  double film_poisson = 0.3;    // nu of the film [-]
};

// (1 - nu^2) / E of a homogeneous half-space [1/Pa]
double compliance(double youngs_modulus, double poisson_ratio);

// closed-form deflection at offset (x, y) from the centre of a 2a-by-2b rectangle under unit
// pressure on a half-space with unit compliance (1 - nu^2)/E = 1: (1/pi) integral dA / r [m]
double love_rectangle(double x, double y, double a, double b);

// surface normal displacement per unit normal pressure at wavenumber alpha [m/Pa * m] of a
// layer (film) bonded to a substrate half-space, from the 6x6 plane-strain boundary system
double layered_compliance_frf(double alpha, double film_thickness, double film_modulus,
                              double film_poisson, double substrate_modulus,
                              double substrate_poisson);

// u = K * p on the grid: the combined normal deflection of both bodies [m] from pressure [Pa]
class DeflectionOperator {
 public:
  DeflectionOperator(const Grid& grid, const ElasticBody& body1, const ElasticBody& body2);

  // u[i*ny+j] = sum over cells of K(i - i', j - j') p[i'*ny+j']; u and p have grid.size()
  void apply(const double* p, double* u) const;
  // influence coefficient at cell offset (di, dj) as sampled [m/Pa]
  double coefficient(int di, int dj) const;

  const Grid& grid() const { return grid_; }

 private:
  Grid grid_;
  int npx_, npy_;                       // padded grid
  Fft2 fft_;
  std::vector<double> kernel_;          // npx * npy coefficients [m/Pa]
  std::vector<Complex> kernel_hat_;     // its spectrum divided by npx * npy
  mutable std::vector<double> pad_;     // scratch
  mutable std::vector<Complex> spec_;   // scratch
};

}  // namespace kneesim::particles
