#include "wear/particles/stress.h"

#include <cmath>

namespace kneesim::particles {
namespace {
}

double von_mises(double sxx, double syy, double szz, double sxy, double sxz, double syz) {
  const double a = sxx - syy, b = syy - szz, c = szz - sxx;
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (sxy * sxy + sxz * sxz + syz * syz));
}

StressSpectra::StressSpectra(const Grid& grid)
    : grid_(grid),
      npx_(2 * grid.nx),
      npy_(grid.periodic_y ? grid.ny : 2 * grid.ny),
      fft_(npx_, npy_) {
  const long nspec = static_cast<long>(npx_) * fft_.nyc();
  p_hat_.assign(nspec, Complex(0.0, 0.0));
  for (auto& s : spec_) s.assign(nspec, Complex(0.0, 0.0));
  real_.assign(static_cast<long>(npx_) * npy_, 0.0);
  for (auto& c : comp_) c.assign(grid.size(), 0.0);
}

void StressSpectra::set_pressure(const std::vector<double>& pressure) {
  const int nx = grid_.nx, ny = grid_.ny;
  std::fill(real_.begin(), real_.end(), 0.0);
  for (int i = 0; i < nx; ++i) {
    std::copy(pressure.begin() + static_cast<long>(i) * ny,
              pressure.begin() + static_cast<long>(i + 1) * ny,
              real_.begin() + static_cast<long>(i) * npy_);
  }
  fft_.forward(real_.data(), p_hat_.data(), nx);
  const double norm = 1.0 / (double(npx_) * npy_);
  for (Complex& c : p_hat_) c *= norm;
}

void StressSpectra::to_grid(std::array<std::vector<double>, 6>& out) const {
  const int nx = grid_.nx, ny = grid_.ny, npy = npy_;
  for (int c = 0; c < 6; ++c) {
    fft_.inverse(spec_[c].data(), real_.data(), nx);
    out[c].resize(grid_.size());
    for (int i = 0; i < nx; ++i) {
      std::copy(real_.begin() + static_cast<long>(i) * npy,
                real_.begin() + static_cast<long>(i) * npy + ny,
                out[c].begin() + static_cast<long>(i) * ny);
    }
  }
}

void StressSpectra::to_von_mises(double* vm) const {
  to_grid(comp_);
  const long n = grid_.size();
  for (long k = 0; k < n; ++k) {
    vm[k] = von_mises(comp_[0][k], comp_[1][k], comp_[2][k], comp_[3][k], comp_[4][k],
                      comp_[5][k]);
  }
}

std::array<Complex, 6> rotate_plane_wave(double c, double s, Complex s11, Complex s22,
                                         Complex s33, Complex s12, Complex s13, Complex s23) {
  std::array<Complex, 6> out;
  out[0] = c * c * s11 + s * s * s22 - 2.0 * c * s * s12;    // xx
  out[1] = s * s * s11 + c * c * s22 + 2.0 * c * s * s12;    // yy
  out[2] = s33;                                              // zz
  out[3] = c * s * (s11 - s22) + (c * c - s * s) * s12;      // xy
  out[4] = c * s13 - s * s23;                                // xz
  out[5] = s * s13 + c * s23;                                // yz
  return out;
}

SubsurfaceStress::SubsurfaceStress(const Grid& grid, double poisson_ratio)
    : nu_(poisson_ratio), spectra_(grid) {}

void SubsurfaceStress::set_traction(const std::vector<double>& pressure, double friction) {
  mu_ = friction;
  spectra_.set_pressure(pressure);
}

void SubsurfaceStress::fill_spectra(double z) const {
  const double nu = nu_, mu = mu_;
  const Complex i1(0.0, 1.0);
  spectra_.fill(
      [&](const Complex& P) -> std::array<Complex, 6> {
        // mean traction: the direction average of the plane-wave response at alpha -> 0
        const Complex in_plane = -0.5 * (1.0 + 2.0 * nu) * P;
        return {in_plane, in_plane, -P, 0.0, -mu * P, 0.0};
      },
      [&](int, int, double kx, double ky, const Complex& P) {
        const Complex Q = mu * P;
        const double alpha = std::hypot(kx, ky), c = kx / alpha, s = ky / alpha;
        const double t = alpha * z, e = std::exp(-t);
        // plane wave along e1 = (c, s): Boussinesq (P) and Cerruti (Q1 = c Q, Q2 = -s Q)
        return rotate_plane_wave(c, s, e * ((t - 1.0) * P + i1 * c * (2.0 - t) * Q),
                                 e * (-2.0 * nu * P + 2.0 * i1 * nu * c * Q),
                                 e * (-(1.0 + t) * P + i1 * t * c * Q), e * (-i1 * s * Q),
                                 e * (i1 * t * P + (t - 1.0) * c * Q), e * (s * Q));
      });
}

void SubsurfaceStress::calc_stress(double z, std::array<std::vector<double>, 6>& out) const {
  fill_spectra(z);
  spectra_.to_grid(out);
}

void SubsurfaceStress::calc_von_mises(double z, double* vm) const {
  fill_spectra(z);
  spectra_.to_von_mises(vm);
}

std::vector<double> refine_levels(const std::vector<double>& coarse, long cells, int nz,
                                  int factor) {
  const int nf = (nz - 1) * factor;
  std::vector<double> fine(static_cast<long>(nf) * cells);
#pragma omp parallel for schedule(static)
  for (int l = 0; l < nf; ++l) {
    const double s = (l + 0.5) / factor;  // position in level units
    const int k = static_cast<int>(s);
    const double w = s - k;
    const double* a = coarse.data() + k * cells;
    const double* b = coarse.data() + (k + 1) * cells;
    double* f = fine.data() + static_cast<long>(l) * cells;
    for (long c = 0; c < cells; ++c) f[c] = (1.0 - w) * a[c] + w * b[c];
  }
  return fine;
}

}  // namespace kneesim::particles
