#include "wear/particles/stress.h"

#include <cmath>

namespace kneesim::particles {
namespace {
constexpr double kPi = 3.14159265358979323846;
}

double von_mises(double sxx, double syy, double szz, double sxy, double sxz, double syz) {
  const double a = sxx - syy, b = syy - szz, c = szz - sxx;
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (sxy * sxy + sxz * sxz + syz * syz));
}

SubsurfaceStress::SubsurfaceStress(const Grid& grid, double poisson_ratio)
    : grid_(grid),
      nu_(poisson_ratio),
      npx_(2 * grid.nx),
      npy_(grid.periodic_y ? grid.ny : 2 * grid.ny),
      fft_(npx_, npy_) {
  const long nspec = static_cast<long>(npx_) * fft_.nyc();
  p_hat_.assign(nspec, Complex(0.0, 0.0));
  for (auto& s : spec_) s.assign(nspec, Complex(0.0, 0.0));
  real_.assign(static_cast<long>(npx_) * npy_, 0.0);
  for (auto& c : comp_) c.assign(grid.size(), 0.0);
}

void SubsurfaceStress::set_traction(const std::vector<double>& pressure, double friction) {
  mu_ = friction;
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

void SubsurfaceStress::calc_stress(double z, std::array<std::vector<double>, 6>& out) const {
  const int nx = grid_.nx, ny = grid_.ny, npx = npx_, npy = npy_, nc = fft_.nyc();
  const double nu = nu_, mu = mu_;
  const Complex i1(0.0, 1.0);
  // frequency responses times the traction spectra
#pragma omp parallel for schedule(static)
  for (int ix = 0; ix < npx; ++ix) {
    const int fx = ix <= npx / 2 ? ix : ix - npx;
    const double kx = 2.0 * kPi * fx / (npx * grid_.dx);
    for (int iy = 0; iy < nc; ++iy) {
      const long k = static_cast<long>(ix) * nc + iy;
      const double ky = 2.0 * kPi * iy / (npy * grid_.dy);
      const Complex P = p_hat_[k], Q = mu * p_hat_[k];
      Complex sxx, syy, szz, sxy, sxz, syz;
      if (ix == npx / 2 || iy == npy / 2) {
        // Nyquist lines: odd responses cannot be represented; drop them
        sxx = syy = szz = sxy = sxz = syz = 0.0;
      } else if (ix == 0 && iy == 0) {
        // mean traction: the direction average of the plane-wave response at alpha -> 0
        sxx = syy = -0.5 * (1.0 + 2.0 * nu) * P;
        szz = -P;
        sxz = -Q;
        sxy = syz = 0.0;
      } else {
        const double alpha = std::hypot(kx, ky), c = kx / alpha, s = ky / alpha;
        const double t = alpha * z, e = std::exp(-t);
        // plane wave along e1 = (c, s): Boussinesq (P) and Cerruti (Q1 = c Q, Q2 = -s Q)
        const Complex s11 = e * ((t - 1.0) * P + i1 * c * (2.0 - t) * Q);
        const Complex s22 = e * (-2.0 * nu * P + 2.0 * i1 * nu * c * Q);
        const Complex s12 = e * (-i1 * s * Q);
        const Complex s33 = e * (-(1.0 + t) * P + i1 * t * c * Q);
        const Complex s13 = e * (i1 * t * P + (t - 1.0) * c * Q);
        const Complex s23 = e * (s * Q);
        // rotate to x, y
        sxx = c * c * s11 + s * s * s22 - 2.0 * c * s * s12;
        syy = s * s * s11 + c * c * s22 + 2.0 * c * s * s12;
        sxy = c * s * (s11 - s22) + (c * c - s * s) * s12;
        sxz = c * s13 - s * s23;
        syz = s * s13 + c * s23;
        szz = s33;
      }
      spec_[0][k] = sxx;
      spec_[1][k] = syy;
      spec_[2][k] = szz;
      spec_[3][k] = sxy;
      spec_[4][k] = sxz;
      spec_[5][k] = syz;
    }
  }
  // back to space, keeping the unpadded part
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

void SubsurfaceStress::calc_von_mises(double z, double* vm) const {
  calc_stress(z, comp_);
  const long n = grid_.size();
  for (long k = 0; k < n; ++k) {
    vm[k] = von_mises(comp_[0][k], comp_[1][k], comp_[2][k], comp_[3][k], comp_[4][k],
                      comp_[5][k]);
  }
}

std::vector<double> calc_von_mises_field(const SubsurfaceStress& stress, int nz, double dz) {
  const long n = stress.grid().size();
  std::vector<double> vm(static_cast<long>(nz) * n);
  for (int k = 0; k < nz; ++k) stress.calc_von_mises(k * dz, vm.data() + k * n);
  return vm;
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
