// Rough surfaces for the particle model: generated (Gaussian or non-Gaussian, periodic) or
// imported from a measured height map.
//
// Generation follows Hu & Tonder (1992): white noise filtered in the frequency domain by the
// square root of the power spectrum of an exponential autocorrelation
// R(tx, ty) = Rq^2 exp(-2.3 sqrt((tx/bx)^2 + (ty/by)^2)) (bx, by: lengths where R falls to 10 %).
// Its power spectrum is proportional to (1 + (qx lx)^2 + (qy ly)^2)^(-3/2), l = b / 2.3. A lay
// (ground or turned finish) is described by Peklenik's gamma = bx / by: x is the sliding
// direction, bx = correlation_length and by = correlation_length / gamma; gamma > 1 is a lay
// along the sliding direction (asperities elongated along x), gamma = 1 isotropic.
//
// The surface is a property of the physical window, not of the grid: the white noise is drawn
// per Fourier mode (m, n) of the window from a counter-based generator keyed by (seed, m, n),
// and a grid keeps the modes below its Nyquist wavenumber. Two grids over the same window thus
// carry the same random phases on the same physical wavenumbers; a coarser grid's Gaussian
// field is the exact spectral truncation of a finer one's. Rejected: white noise per grid
// point (every grid size gives another surface) and bilinear point resampling of one fine
// surface (aliases the short wavelengths onto the coarse grid).
//
// The exponential autocorrelation is not differentiable at the origin: its spectrum falls as
// q^-3 and the rms slope grows without bound as the grid refines, so contact spots and the
// stress fields under them never converge. A measured Rq is however band-limited by the
// instrument: ISO 3274 / ISO 16610-21 apply a Gaussian short-wavelength filter lambda_s
// (amplitude transmission exp(-ln 2 (lambda_s / lambda)^2), 50 % at lambda = lambda_s).
// With lambda_s > 0 the same filter is applied to the generated spectrum, and the Rq,
// skewness and kurtosis targets are those of the filtered surface, as measured.
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
  double correlation_length = 0.0; // 10 % autocorrelation length along x (sliding) [m]
  std::uint64_t seed = 1;          // random seed [-]
  double lambda_s = 0.0;           // short-wavelength cutoff (ISO Gaussian, 50 %); 0 = none [m]
  double gamma = 1.0;              // Peklenik lay ratio bx / by; across x: correlation_length / gamma [-]
};

struct SurfaceStats {
  double mean = 0.0;      // [m]
  double rq = 0.0;        // [m]
  double skewness = 0.0;  // [-]
  double kurtosis = 0.0;  // [-]
};

// heights (grid.size(), [m], zero mean) of a surface periodic in both directions over the
// window nx dx by ny dy; throws InputError naming `source` for Rq, correlation length or gamma
// <= 0, lambda_s < 0, or moments that no Fleishman transform reaches (kurtosis below
// 1 + skewness^2 or far beyond it)
std::vector<double> make_rough_surface(const Grid& grid, const SurfaceSpec& spec,
                                       const std::string& source);

SurfaceStats calc_surface_stats(const std::vector<double>& heights);

// rms slopes along x and y and rms curvature (Laplacian / 2, the mean of the two principal
// curvatures) of a periodic surface (grid.size()), by spectral differentiation
struct SurfaceGradients {
  double slope_x = 0.0;    // rms dz/dx [-]
  double slope_y = 0.0;    // rms dz/dy [-]
  double curvature = 0.0;  // rms (d2z/dx2 + d2z/dy2) / 2 [1/m]
};
SurfaceGradients calc_surface_gradients(const Grid& grid, const std::vector<double>& heights);

// correlation length of a periodic surface along x (along_x) or y: the first lag at which
// its autocorrelation falls to 10 %, linearly interpolated between cells [m]
double measure_correlation_length(const Grid& grid, const std::vector<double>& heights, bool along_x);

// coefficients (b, c, d) of the Fleishman transform for a target skewness and kurtosis;
// returns false when Newton's method finds none
bool solve_fleishman(double skewness, double kurtosis, double& b, double& c, double& d);

// amplitude transmission of the ISO 16610-21 Gaussian low-pass with cutoff lambda_s [m] at
// wavenumber q [rad/m]: exp(-ln 2 (lambda_s q / 2 pi)^2); 1 when lambda_s = 0
double lambda_s_transmission(double q, double lambda_s);

// filters a field periodic in both directions (grid.size()) in place with the lambda_s
// Gaussian low-pass; the mean is kept; nothing happens when lambda_s = 0
void apply_lambda_s_filter(const Grid& grid, double lambda_s, std::vector<double>& field);

}  // namespace kneesim::particles
