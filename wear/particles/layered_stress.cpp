#include "wear/particles/layered_stress.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cassert>
#include <cmath>

namespace kneesim::particles {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kThickFilm = 40.0;  // alpha t beyond which the substrate is invisible
constexpr int kCellPoints = 8;       // quadrature points per axis over a quarter frequency cell
constexpr int kCoefs = 16;           // stored numbers per frequency (solve_frequency)

// One plane-strain solution of a layer (shear modulus G, Poisson ratio nu) for the Fourier
// mode exp(i alpha x1), at w = alpha (z - z_ref) from its reference plane, decaying (s = 1) or
// growing (s = -1) with depth, with e = exp(-s w) given:
//   G alpha u1 = i (p - n w) e,  G alpha u3 = (q + m w) e,
//   m = (p + s q) / kappa,  n = (s p + q) / kappa,  kappa = 3 - 4 nu
// (the w terms are fixed by the Navier equations; the same basis as plane_strain_basis in
// deflection.cpp, with the phase of a pressure load factored out so that p, q and every
// entry of the boundary system are real). Returns G alpha u1 / i, G alpha u3, sigma_11,
// sigma_33 and sigma_13 / i per unit (p, q) scale.
struct Mode {
  double u1, u3, s11, s33, s13;
};

Mode plane_strain_mode(double nu, double s, double w, double e, double p, double q) {
  const double kappa = 3.0 - 4.0 * nu;
  const double m = (p + s * q) / kappa, n = (s * p + q) / kappa;
  return {(p - n * w) * e, (q + m * w) * e, (-4.0 * nu * m - 2.0 * p + 2.0 * n * w) * e,
          (2.0 * (1.0 - 2.0 * nu) * m - 2.0 * s * q - 2.0 * s * m * w) * e,
          (-n - s * p + q + 2.0 * m * w) * e};
}

// Plane-strain and antiplane coefficients at alpha t = at into c[kCoefs]: (p, q) of the
// film's decaying solution (reference z = 0), of its growing one (reference z = t) and of the
// substrate's (reference z = t), first for a unit pressure, then for a unit in-plane shear
// Q1; then the antiplane amplitudes a, b, d (below); then exp(-alpha t), or 0 for a film
// half-space.
void solve_frequency(double at, double nuf, double nus, double gf_over_gs, double* c) {
  std::fill(c, c + kCoefs, 0.0);
  if (at > kThickFilm) {
    // film half-space: sigma_33 = -1, sigma_13 = 0 (pressure) or 0, -1 (shear) at z = 0
    c[0] = 0.5 * (1.0 - 2.0 * nuf);
    c[1] = 1.0 - nuf;
    c[6] = 1.0 - nuf;
    c[7] = 0.5 * (1.0 - 2.0 * nuf);
    c[12] = 1.0;
    return;
  }
  // rows: surface sigma_33, sigma_13; interface u1, u3 (G_f alpha u, so the film-minus-
  // substrate difference reads u_f - (G_f / G_s) u_s), sigma_33, sigma_13
  const double et = std::exp(-at);
  Eigen::Matrix<double, 6, 6> a;
  for (int k = 0; k < 2; ++k) {
    const double p = (k == 0) ? 1.0 : 0.0, q = 1.0 - p;
    const Mode top_dec = plane_strain_mode(nuf, 1.0, 0.0, 1.0, p, q);
    const Mode top_grow = plane_strain_mode(nuf, -1.0, -at, et, p, q);
    const Mode int_dec = plane_strain_mode(nuf, 1.0, at, et, p, q);
    const Mode int_grow = plane_strain_mode(nuf, -1.0, 0.0, 1.0, p, q);
    const Mode sub = plane_strain_mode(nus, 1.0, 0.0, 1.0, p, q);
    a.col(k) << top_dec.s33, top_dec.s13, int_dec.u1, int_dec.u3, int_dec.s33, int_dec.s13;
    a.col(2 + k) << top_grow.s33, top_grow.s13, int_grow.u1, int_grow.u3, int_grow.s33,
        int_grow.s13;
    a.col(4 + k) << 0.0, 0.0, -gf_over_gs * sub.u1, -gf_over_gs * sub.u3, -sub.s33, -sub.s13;
  }
  // a unit pressure: sigma_33 = -1; a unit shear Q1: its solution is -i times the real one
  // with sigma_13 / i = -1 (so that sigma_13 = -1 and every other phase turns with it)
  Eigen::Matrix<double, 6, 2> rhs = Eigen::Matrix<double, 6, 2>::Zero();
  rhs(0, 0) = -1.0;
  rhs(1, 1) = -1.0;
  const Eigen::Matrix<double, 6, 2> x = a.partialPivLu().solve(rhs);
  for (int r = 0; r < 6; ++r) {
    c[r] = x(r, 0);
    c[6 + r] = x(r, 1);
  }
  // antiplane shear: u2 = A exp(-alpha z) + B exp(-alpha (t - z)) in the film and
  // C exp(-alpha (z - t)) in the substrate; sigma_23 = -Q2 at z = 0 and continuity of u2 and
  // sigma_23 at z = t give, with r = (G_f - G_s) / (G_f + G_s) and E = exp(-alpha t),
  // G_f alpha (A, B) = Q2 (a, b), a = 1 / (1 - r E^2), b = r E a, and in the substrate
  // sigma_23 = -Q2 d exp(-alpha (z - t)) with d = (1 - r) E a
  const double r = (gf_over_gs - 1.0) / (gf_over_gs + 1.0);
  const double amp = 1.0 / (1.0 - r * et * et);
  c[12] = amp;
  c[13] = r * et * amp;
  c[14] = (1.0 - r) * et * amp;
  c[15] = et;
}

// G_f alpha u1 / i at the surface per unit pressure; the surface strain du1/dx1 = i alpha u1
// is minus this over G_f
double surface_u1(double at, double nuf, const double* c) {
  const Mode dec = plane_strain_mode(nuf, 1.0, 0.0, 1.0, c[0], c[1]);
  const Mode grow = plane_strain_mode(nuf, -1.0, -at, std::exp(-at), c[2], c[3]);
  return dec.u1 + grow.u1;
}

}  // namespace

LayeredSubsurfaceStress::LayeredSubsurfaceStress(const Grid& grid, double film_thickness,
                                                 double film_modulus, double film_poisson,
                                                 double substrate_modulus,
                                                 double substrate_poisson)
    : t_(film_thickness), nu_f_(film_poisson), nu_s_(substrate_poisson), spectra_(grid) {
  assert(film_thickness > 0.0 && film_modulus > 0.0 && substrate_modulus > 0.0);
  const double gf = film_modulus / (2.0 * (1.0 + film_poisson));
  const double gs = substrate_modulus / (2.0 * (1.0 + substrate_poisson));
  const double t = t_, nuf = nu_f_, nus = nu_s_, ratio = gf / gs;
  const int nc = spectra_.nyc(), npx = spectra_.npx(), npy = spectra_.npy(), nrow = npx / 2 + 1;
  const double dx = grid.dx, dy = grid.dy;

  // the responses depend on |k| only: one row per |kx|
  coef_.assign(static_cast<long>(nrow) * nc * kCoefs, 0.0);
#pragma omp parallel for schedule(dynamic, 4)
  for (int ix = 0; ix < nrow; ++ix) {
    const double kx = 2.0 * kPi * ix / (npx * dx);
    for (int iy = 0; iy < nc; ++iy) {
      const double ky = 2.0 * kPi * iy / (npy * dy);
      solve_frequency(std::hypot(kx, ky) * t, nuf, nus, ratio,
                      &coef_[(static_cast<long>(ix) * nc + iy) * kCoefs]);
    }
  }

  // zero wavenumber: the shared in-plane strain is the surface strain averaged over the
  // central frequency cell (midpoint rule on a quarter; see the header)
  const double hx = kPi / (npx * dx), hy = kPi / (npy * dy);
  double u1_mean = 0.0;
  double c[kCoefs];
  for (int i = 0; i < kCellPoints; ++i) {
    for (int j = 0; j < kCellPoints; ++j) {
      const double at =
          std::hypot((i + 0.5) * hx / kCellPoints, (j + 0.5) * hy / kCellPoints) * t;
      solve_frequency(at, nuf, nus, ratio, c);
      u1_mean += surface_u1(at, nuf, c);
    }
  }
  u1_mean /= kCellPoints * kCellPoints;
  // equibiaxial strain e = -u1 / (2 G_f) per unit pressure, sigma_zz = -1:
  // sigma_xx = (E e - nu) / (1 - nu) in each layer
  const double e = -0.5 * u1_mean / gf;
  mean_xx_f_ = (film_modulus * e - nuf) / (1.0 - nuf);
  mean_xx_s_ = (substrate_modulus * e - nus) / (1.0 - nus);
}

void LayeredSubsurfaceStress::set_traction(const std::vector<double>& pressure,
                                           double friction) {
  mu_ = friction;
  spectra_.set_pressure(pressure);
}

void LayeredSubsurfaceStress::fill_spectra(double z) const {
  assert(z >= 0.0);
  const int nc = spectra_.nyc();
  const double mu = mu_, t = t_, nuf = nu_f_, nus = nu_s_;
  const bool film = z < t;
  const double nu = film ? nuf : nus;
  const double mean_xx = film ? mean_xx_f_ : mean_xx_s_;
  const Complex i1(0.0, 1.0);
  spectra_.fill(
      [&](const Complex& P) -> std::array<Complex, 6> {
        // mean traction: uniform normal and shear stress, shared in-plane strain (header)
        return {mean_xx * P, mean_xx * P, -P, 0.0, -mu * P, 0.0};
      },
      [&](int fx, int iy, double kx, double ky, const Complex& P) {
        const Complex Q = mu * P;
        const double alpha = std::hypot(kx, ky), c = kx / alpha, s = ky / alpha;
        const double* cf = &coef_[(static_cast<long>(fx < 0 ? -fx : fx) * nc + iy) * kCoefs];
        // real plane-strain responses to a unit P (p*) and a unit Q1 (q*), and antiplane
        // amplitudes: sigma_12 = i Q2 r12, sigma_23 = -Q2 r23
        double p11, p33, p13, q11, q33, q13, r12, r23;
        if (film) {
          const double w = alpha * z, ed = std::exp(-w);
          // exp(-alpha (t - z)) = exp(-alpha t) / exp(-alpha z), with exp(-alpha z) >=
          // exp(-40) whenever the growing solutions are present
          const double wg = alpha * (z - t), eg = cf[15] > 0.0 ? cf[15] / ed : 0.0;
          const Mode dp = plane_strain_mode(nuf, 1.0, w, ed, cf[0], cf[1]);
          const Mode gp = plane_strain_mode(nuf, -1.0, wg, eg, cf[2], cf[3]);
          const Mode dq = plane_strain_mode(nuf, 1.0, w, ed, cf[6], cf[7]);
          const Mode gq = plane_strain_mode(nuf, -1.0, wg, eg, cf[8], cf[9]);
          p11 = dp.s11 + gp.s11;
          p33 = dp.s33 + gp.s33;
          p13 = dp.s13 + gp.s13;
          q11 = dq.s11 + gq.s11;
          q33 = dq.s33 + gq.s33;
          q13 = dq.s13 + gq.s13;
          r12 = cf[12] * ed + cf[13] * eg;
          r23 = cf[12] * ed - cf[13] * eg;
        } else {
          const double w = alpha * (z - t), e = std::exp(-w);
          const Mode sp = plane_strain_mode(nus, 1.0, w, e, cf[4], cf[5]);
          const Mode sq = plane_strain_mode(nus, 1.0, w, e, cf[10], cf[11]);
          p11 = sp.s11;
          p33 = sp.s33;
          p13 = sp.s13;
          q11 = sq.s11;
          q33 = sq.s33;
          q13 = sq.s13;
          r12 = r23 = cf[14] * e;
        }
        // plane wave along e1 = (c, s): pressure P, shear Q1 = c Q in-plane, Q2 = -s Q across
        const Complex q1 = c * Q, q2 = -s * Q;
        const Complex s11 = p11 * P - i1 * q11 * q1;
        const Complex s33 = p33 * P - i1 * q33 * q1;
        const Complex s13 = i1 * p13 * P + q13 * q1;
        const Complex s22 = nu * (s11 + s33);  // plane strain
        const Complex s12 = i1 * r12 * q2;
        const Complex s23 = -r23 * q2;
        return rotate_plane_wave(c, s, s11, s22, s33, s12, s13, s23);
      });
}

void LayeredSubsurfaceStress::calc_stress(double z, std::array<std::vector<double>, 6>& out) const {
  fill_spectra(z);
  spectra_.to_grid(out);
}

void LayeredSubsurfaceStress::calc_von_mises(double z, double* vm) const {
  fill_spectra(z);
  spectra_.to_von_mises(vm);
}

}  // namespace kneesim::particles
