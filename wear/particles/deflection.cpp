#include "wear/particles/deflection.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace kneesim::particles {
namespace {

constexpr double kPi = 3.14159265358979323846;

// double antiderivative of 1/sqrt(X^2 + Y^2) at a rectangle corner
double love_corner(double x, double y) {
  double g = 0.0;
  if (x != 0.0) g += x * std::asinh(y / std::abs(x));
  if (y != 0.0) g += y * std::asinh(x / std::abs(y));
  return g;
}

// sum over j > M of 1 / j^3
double zeta3_tail(int m) {
  double s = 0.0;
  for (int j = 200000; j > m; --j) s += 1.0 / (double(j) * j * j);
  return s;
}

// basis solutions of plane-strain elasticity for a Fourier mode exp(i alpha x): displacement
// (a0 + b0 z, a2 + b2 z) exp(-s alpha z) with b fixed by the Navier equations; returns
// (u1, u3, sigma_zz, sigma_1z) at relative depth zr for unit a0 (k = 0) or unit a2 (k = 1)
Eigen::Vector4cd plane_strain_basis(double g, double nu, double s, double alpha, double zr,
                                    int k) {
  const Complex i1(0.0, 1.0);
  const Complex a0 = (k == 0) ? 1.0 : 0.0, a2 = (k == 1) ? 1.0 : 0.0;
  const Complex b0 = (s * a0 + i1 * a2) * alpha / (4.0 * nu - 3.0);
  const Complex b2 = (i1 * a0 - s * a2) * alpha / (4.0 * nu - 3.0);
  const double e = std::exp(-s * alpha * zr);
  const Complex u1 = (a0 + b0 * zr) * e, u3 = (a2 + b2 * zr) * e;
  const Complex du1 = b0 * e - s * alpha * u1, du3 = b2 * e - s * alpha * u3;
  const double lambda = 2.0 * g * nu / (1.0 - 2.0 * nu);
  const Complex div = i1 * alpha * u1 + du3;
  Eigen::Vector4cd out;
  out << u1, u3, lambda * div + 2.0 * g * du3, g * (du1 + i1 * alpha * u3);
  return out;
}

}  // namespace

double compliance(double youngs_modulus, double poisson_ratio) {
  return (1.0 - poisson_ratio * poisson_ratio) / youngs_modulus;
}

double love_rectangle(double x, double y, double a, double b) {
  return (love_corner(x + a, y + b) - love_corner(x + a, y - b) - love_corner(x - a, y + b) +
          love_corner(x - a, y - b)) /
         kPi;
}

double layered_compliance_frf(double alpha, double h, double ef, double nuf, double es,
                              double nus) {
  const double gf = ef / (2.0 * (1.0 + nuf)), gs = es / (2.0 * (1.0 + nus));
  if (alpha * h > 40.0) return (1.0 - nuf) / (gf * alpha);
  // unknowns: film decaying (ref z = 0), film growing (ref z = h), substrate decaying (z = h)
  Eigen::Matrix<Complex, 6, 6> a = Eigen::Matrix<Complex, 6, 6>::Zero();
  Eigen::Matrix<Complex, 6, 1> rhs = Eigen::Matrix<Complex, 6, 1>::Zero();
  const double u_scale = gf * alpha;  // puts displacement rows on the scale of stress rows
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector4cd top_dec = plane_strain_basis(gf, nuf, 1.0, alpha, 0.0, k);
    const Eigen::Vector4cd top_grow = plane_strain_basis(gf, nuf, -1.0, alpha, -h, k);
    const Eigen::Vector4cd int_dec = plane_strain_basis(gf, nuf, 1.0, alpha, h, k);
    const Eigen::Vector4cd int_grow = plane_strain_basis(gf, nuf, -1.0, alpha, 0.0, k);
    const Eigen::Vector4cd sub = plane_strain_basis(gs, nus, 1.0, alpha, 0.0, k);
    // surface: sigma_zz = -1 (unit pressure), sigma_xz = 0
    a(0, k) = top_dec(2);
    a(0, 2 + k) = top_grow(2);
    a(1, k) = top_dec(3);
    a(1, 2 + k) = top_grow(3);
    // interface: displacement and traction continuity
    for (int r = 0; r < 4; ++r) {
      const double w = (r < 2) ? u_scale : 1.0;
      a(2 + r, k) = w * int_dec(r);
      a(2 + r, 2 + k) = w * int_grow(r);
      a(2 + r, 4 + k) = -w * sub(r);
    }
  }
  rhs(0) = -1.0;
  const Eigen::Matrix<Complex, 6, 1> c = a.partialPivLu().solve(rhs);
  Complex u3 = 0.0;
  for (int k = 0; k < 2; ++k) {
    u3 += c(k) * plane_strain_basis(gf, nuf, 1.0, alpha, 0.0, k)(1);
    u3 += c(2 + k) * plane_strain_basis(gf, nuf, -1.0, alpha, -h, k)(1);
  }
  return u3.real();
}

DeflectionOperator::DeflectionOperator(const Grid& grid, const ElasticBody& body1,
                                       const ElasticBody& body2)
    : grid_(grid),
      npx_(2 * grid.nx),
      npy_(grid.periodic_y ? grid.ny : 2 * grid.ny),
      fft_(npx_, npy_) {
  const int nx = grid.nx, ny = grid.ny, npx = npx_, npy = npy_;
  const double dx = grid.dx, dy = grid.dy, area = grid.cell_area();
  const double ly = ny * dy;
  const bool periodic = grid.periodic_y;

  // surface compliance (film if layered) and the substrate-minus-film excess of each body
  double k_top = 0.0;
  struct Film { double k_excess, t, ef, nuf, es, nus; };
  std::vector<Film> films;
  for (const ElasticBody* b : {&body1, &body2}) {
    if (b->film_thickness > 0.0) {
      const double kf = compliance(b->film_modulus, b->film_poisson);
      k_top += kf;
      films.push_back({compliance(b->youngs_modulus, b->poisson_ratio) - kf, b->film_thickness,
                       b->film_modulus, b->film_poisson, b->youngs_modulus, b->poisson_ratio});
    } else {
      k_top += compliance(b->youngs_modulus, b->poisson_ratio);
    }
  }

  // offsets of the padded kernel array; the middle row/column of a padded axis is unused
  auto off_x = [&](int ix) { return ix < nx ? ix : ix - npx; };
  auto off_y = [&](int iy) {
    if (periodic) return iy <= ny / 2 ? iy : iy - ny;
    return iy < ny ? iy : iy - npy;
  };
  // periodic images each side, reaching well beyond the grid length so that the closed-form
  // tail (an expansion in x / distance) is accurate
  const int images = periodic ? std::max(8, static_cast<int>(std::ceil(8.0 * nx * dx / ly))) : 0;
  const double tail = periodic ? zeta3_tail(images) : 0.0;

  // point-sampled 1/sqrt(r^2 + c^2) summed over periodic images, constants removed
  auto point_sum = [&](double x, double y, double c) {
    double s = 1.0 / std::sqrt(x * x + y * y + c * c);
    for (int j = 1; j <= images; ++j) {
      const double d = j * ly;
      s += 1.0 / std::sqrt(x * x + (y + d) * (y + d) + c * c) +
           1.0 / std::sqrt(x * x + (y - d) * (y - d) + c * c) - 2.0 / std::sqrt(d * d + c * c);
    }
    if (periodic) s += (2.0 * y * y - x * x - c * c) / (ly * ly * ly) * tail;
    return s;
  };

  kernel_.assign(static_cast<long>(npx) * npy, 0.0);
#pragma omp parallel for schedule(static)
  for (int ix = 0; ix < npx; ++ix) {
    if (ix == nx) continue;
    const double x = off_x(ix) * dx;
    for (int iy = 0; iy < npy; ++iy) {
      if (!periodic && iy == ny) continue;
      const double y = off_y(iy) * dy;
      // homogeneous surface compliance: Love's rectangle over all images
      double s = love_rectangle(x, y, 0.5 * dx, 0.5 * dy);
      for (int j = 1; j <= images; ++j) {
        const double d = j * ly;
        s += love_rectangle(x, y + d, 0.5 * dx, 0.5 * dy) +
             love_rectangle(x, y - d, 0.5 * dx, 0.5 * dy) -
             2.0 * love_rectangle(0.0, d, 0.5 * dx, 0.5 * dy);
      }
      if (periodic) s += area / kPi * (2.0 * y * y - x * x) / (ly * ly * ly) * tail;
      double k = k_top * s;
      // layered bodies: smooth far-field excess of the substrate
      for (const Film& f : films) k += f.k_excess * area / kPi * point_sum(x, y, f.t);
      kernel_[static_cast<long>(ix) * npy + iy] = k;
    }
  }

  // layered bodies: the exponentially decaying remainder, sampled in the frequency domain
  const int nc = fft_.nyc();
  kernel_hat_.assign(static_cast<long>(npx) * nc, Complex(0.0, 0.0));
  if (!films.empty()) {
    std::vector<Complex> rem(static_cast<long>(npx) * nc);
    std::vector<double> rem_x(static_cast<long>(npx) * npy);
#pragma omp parallel for schedule(static)
    for (int ix = 0; ix < npx; ++ix) {
      const double kx = 2.0 * kPi * off_x(ix) / (npx * dx);
      for (int iy = 0; iy < nc; ++iy) {
        const double ky = 2.0 * kPi * iy / (npy * dy);
        double r = 0.0;
        for (const Film& f : films) {
          const double kf = compliance(f.ef, f.nuf);
          // the remainder is finite at alpha -> 0; evaluate it just above
          const double alpha = std::max(std::hypot(kx, ky), 1e-3 / f.t);
          const double c = layered_compliance_frf(alpha, f.t, f.ef, f.nuf, f.es, f.nus);
          r += c - 2.0 * kf / alpha - 2.0 * f.k_excess * std::exp(-alpha * f.t) / alpha;
        }
        rem[static_cast<long>(ix) * nc + iy] = r;
      }
    }
    fft_.inverse(rem.data(), rem_x.data(), npx);
    const double norm = 1.0 / (double(npx) * npy);
    for (int ix = 0; ix < npx; ++ix) {
      for (int iy = 0; iy < npy; ++iy) {
        if (ix == nx || (!periodic && iy == ny)) continue;
        kernel_[static_cast<long>(ix) * npy + iy] += rem_x[static_cast<long>(ix) * npy + iy] * norm;
      }
    }
  }

  fft_.forward(kernel_.data(), kernel_hat_.data(), npx);
  const double norm = 1.0 / (double(npx) * npy);
  for (Complex& c : kernel_hat_) c *= norm;
  pad_.assign(static_cast<long>(npx) * npy, 0.0);
  spec_.assign(static_cast<long>(npx) * nc, Complex(0.0, 0.0));
}

double DeflectionOperator::coefficient(int di, int dj) const {
  const int ix = di >= 0 ? di : di + npx_;
  const int iy = dj >= 0 ? dj : dj + npy_;
  return kernel_[static_cast<long>(ix) * npy_ + iy];
}

void DeflectionOperator::apply(const double* p, double* u) const {
  const int nx = grid_.nx, ny = grid_.ny, npy = npy_;
  for (int i = 0; i < nx; ++i) {
    std::copy(p + static_cast<long>(i) * ny, p + static_cast<long>(i + 1) * ny,
              pad_.begin() + static_cast<long>(i) * npy);
  }
  fft_.forward(pad_.data(), spec_.data(), nx);
  const long n = static_cast<long>(spec_.size());
  for (long k = 0; k < n; ++k) spec_[k] *= kernel_hat_[k];
  fft_.inverse(spec_.data(), pad_.data(), nx);
  for (int i = 0; i < nx; ++i) {
    std::copy(pad_.begin() + static_cast<long>(i) * npy,
              pad_.begin() + static_cast<long>(i) * npy + ny, u + static_cast<long>(i) * ny);
  }
  // the padding columns of pad_ must be zero again before the next forward transform
  if (npy != ny) {
    for (int i = 0; i < nx; ++i) {
      std::fill(pad_.begin() + static_cast<long>(i) * npy + ny,
                pad_.begin() + static_cast<long>(i + 1) * npy, 0.0);
    }
  }
}

}  // namespace kneesim::particles
