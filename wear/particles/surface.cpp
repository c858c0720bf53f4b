#include "wear/particles/surface.h"

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>

#include "engine/errors.h"
#include "wear/particles/fft.h"

namespace kneesim::particles {
namespace {

constexpr double kPi = 3.14159265358979323846;

// SplitMix64 finaliser (Steele, Lea & Flood 2014): a portable, well-mixed 64-bit hash
std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// complex standard normal deviate of the window's Fourier mode (m, n), n >= 0, from the seed
// alone (Box-Muller on two hashed uniforms), so every grid draws the same value for a mode
Complex mode_noise(std::uint64_t seed, long m, long n) {
  const std::uint64_t key = mix64(seed ^ mix64(static_cast<std::uint64_t>(m) * 0xd1b54a32d192ed03ULL ^
                                               mix64(static_cast<std::uint64_t>(n))));
  const double scale = 1.0 / 9007199254740992.0;  // 2^-53
  const double u1 = (static_cast<double>(mix64(key) >> 11) + 0.5) * scale;
  const double u2 = (static_cast<double>(mix64(key + 1) >> 11) + 0.5) * scale;
  const double r = std::sqrt(-2.0 * std::log(u1));
  return {r * std::cos(2.0 * kPi * u2), r * std::sin(2.0 * kPi * u2)};
}

Eigen::Vector3d fleishman_residual(const Eigen::Vector3d& v, double g1, double g2) {
  const double b = v(0), c = v(1), d = v(2);
  Eigen::Vector3d f;
  f(0) = b * b + 6 * b * d + 2 * c * c + 15 * d * d - 1.0;
  f(1) = 2 * c * (b * b + 24 * b * d + 105 * d * d + 2) - g1;
  f(2) = 24 * (b * d + c * c * (1 + b * b + 28 * b * d) +
               d * d * (12 + 48 * b * d + 141 * c * c + 225 * d * d)) -
         g2;
  return f;
}

}  // namespace

bool solve_fleishman(double skewness, double kurtosis, double& b, double& c, double& d) {
  const double g2 = kurtosis - 3.0;
  // a few starting points; damped Newton with a finite-difference Jacobian
  for (double d0 : {0.0, 0.05, 0.15, -0.05}) {
    Eigen::Vector3d v(1.0 - 3 * d0, skewness / 6.0, d0);
    for (int it = 0; it < 200; ++it) {
      const Eigen::Vector3d f = fleishman_residual(v, skewness, g2);
      if (f.norm() < 1e-13) {
        if (v(0) > 0.0) {
          b = v(0), c = v(1), d = v(2);
          return true;
        }
        break;
      }
      Eigen::Matrix3d jac;
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector3d w = v;
        const double h = 1e-7;
        w(k) += h;
        jac.col(k) = (fleishman_residual(w, skewness, g2) - f) / h;
      }
      Eigen::Vector3d step = jac.fullPivLu().solve(-f);
      double lambda = 1.0;
      while (lambda > 1e-4 &&
             fleishman_residual(v + lambda * step, skewness, g2).norm() > f.norm()) {
        lambda *= 0.5;
      }
      v += lambda * step;
    }
  }
  return false;
}

double lambda_s_transmission(double q, double lambda_s) {
  const double w = lambda_s * q / (2.0 * kPi);
  return std::exp(-std::log(2.0) * w * w);
}

void apply_lambda_s_filter(const Grid& grid, double lambda_s, std::vector<double>& field) {
  if (!(lambda_s > 0.0)) return;
  const int nx = grid.nx, ny = grid.ny;
  Fft2 fft(nx, ny);
  const int nc = fft.nyc();
  std::vector<Complex> spec(static_cast<long>(nx) * nc);
  fft.forward(field.data(), spec.data(), nx);
  const double norm = 1.0 / (double(nx) * ny);
  for (int ix = 0; ix < nx; ++ix) {
    const int m = ix <= nx / 2 ? ix : ix - nx;
    const double qx = 2.0 * kPi * m / (nx * grid.dx);
    for (int iy = 0; iy < nc; ++iy) {
      const double qy = 2.0 * kPi * iy / (ny * grid.dy);
      spec[static_cast<long>(ix) * nc + iy] *= norm * lambda_s_transmission(std::hypot(qx, qy), lambda_s);
    }
  }
  fft.inverse(spec.data(), field.data(), nx);
}

SurfaceStats calc_surface_stats(const std::vector<double>& h) {
  SurfaceStats s;
  const double n = static_cast<double>(h.size());
  for (double v : h) s.mean += v;
  s.mean /= n;
  double m2 = 0.0, m3 = 0.0, m4 = 0.0;
  for (double v : h) {
    const double e = v - s.mean;
    m2 += e * e;
    m3 += e * e * e;
    m4 += e * e * e * e;
  }
  m2 /= n, m3 /= n, m4 /= n;
  s.rq = std::sqrt(m2);
  s.skewness = m3 / (m2 * s.rq);
  s.kurtosis = m4 / (m2 * m2);
  return s;
}

SurfaceGradients calc_surface_gradients(const Grid& grid, const std::vector<double>& h) {
  const int nx = grid.nx, ny = grid.ny;
  Fft2 fft(nx, ny);
  const int nc = fft.nyc();
  std::vector<Complex> spec(static_cast<long>(nx) * nc);
  std::vector<double> work(h);
  fft.forward(work.data(), spec.data(), nx);
  // Parseval over the half spectrum: columns 0 and ny/2 once, the others twice
  double sx = 0.0, sy = 0.0, sc = 0.0;
  for (int ix = 0; ix < nx; ++ix) {
    const int m = ix <= nx / 2 ? ix : ix - nx;
    const double qx = (2 * m == nx) ? 0.0 : 2.0 * kPi * m / (nx * grid.dx);
    for (int iy = 0; iy < nc; ++iy) {
      const double qy = (2 * iy == ny) ? 0.0 : 2.0 * kPi * iy / (ny * grid.dy);
      const double w = (iy == 0 || 2 * iy == ny) ? 1.0 : 2.0;
      const double a2 = std::norm(spec[static_cast<long>(ix) * nc + iy]);
      sx += w * qx * qx * a2;
      sy += w * qy * qy * a2;
      sc += w * 0.25 * (qx * qx + qy * qy) * (qx * qx + qy * qy) * a2;
    }
  }
  const double n2 = double(nx) * ny * double(nx) * ny;
  return {std::sqrt(sx / n2), std::sqrt(sy / n2), std::sqrt(sc / n2)};
}

double measure_correlation_length(const Grid& grid, const std::vector<double>& h, bool along_x) {
  // circular autocorrelation by the Wiener-Khinchin theorem: inverse transform of |H|^2
  const int nx = grid.nx, ny = grid.ny;
  Fft2 fft(nx, ny);
  const int nc = fft.nyc();
  std::vector<Complex> spec(static_cast<long>(nx) * nc);
  std::vector<double> acf(h);
  fft.forward(acf.data(), spec.data(), nx);
  spec[0] = 0.0;  // mean
  for (Complex& v : spec) v = std::norm(v);
  fft.inverse(spec.data(), acf.data(), nx);
  const int n = along_x ? nx : ny;
  const double d = along_x ? grid.dx : grid.dy;
  double prev = 1.0;
  for (int lag = 1; lag <= n / 2; ++lag) {
    const double r = (along_x ? acf[static_cast<long>(lag) * ny] : acf[lag]) / acf[0];
    if (r <= 0.1) return d * (lag - 1 + (prev - 0.1) / (prev - r));
    prev = r;
  }
  return 0.5 * n * d;
}

std::vector<double> make_rough_surface(const Grid& grid, const SurfaceSpec& spec,
                                       const std::string& source) {
  char buf[256];
  if (!(spec.gamma > 0.0)) {
    std::snprintf(buf, sizeof buf, "%s: Peklenik gamma = %g is not allowed; it must be > 0",
                  source.c_str(), spec.gamma);
    throw InputError(buf);
  }
  if (!(spec.rq > 0.0) || !(spec.correlation_length > 0.0)) {
    std::snprintf(buf, sizeof buf,
                  "%s: roughness Rq = %g nm and correlation length = %g nm are not allowed; both "
                  "must be > 0",
                  source.c_str(), spec.rq * 1e9, spec.correlation_length * 1e9);
    throw InputError(buf);
  }
  if (!(spec.lambda_s >= 0.0)) {
    std::snprintf(buf, sizeof buf, "%s: lambda_s = %g nm is not allowed; it must be >= 0",
                  source.c_str(), spec.lambda_s * 1e9);
    throw InputError(buf);
  }
  const int nx = grid.nx, ny = grid.ny;
  const long n = grid.size();
  Fft2 fft(nx, ny);
  const int nc = fft.nyc();

  // spectrum: per-mode noise times the square root of the exponential autocorrelation's power
  // spectrum, (1 + (q l)^2)^(-3/2) with l = beta / 2.3, times the lambda_s filter; modes at or
  // beyond a grid's Nyquist index are left out, so a coarser grid holds a subset of the modes
  const double ell_x = spec.correlation_length / 2.3;
  const double ell_y = ell_x / spec.gamma;
  std::vector<Complex> spectrum(static_cast<long>(nx) * nc, Complex(0.0, 0.0));
  for (int ix = 0; ix < nx; ++ix) {
    const long m = ix <= nx / 2 ? ix : ix - nx;
    if (2 * std::abs(m) >= nx) continue;
    const double qx = 2.0 * kPi * m / (nx * grid.dx);
    for (int iy = 0; iy < nc; ++iy) {
      const long mn = iy;
      if (2 * mn >= ny || (mn == 0 && m == 0)) continue;  // Nyquist column, mean
      const double qy = 2.0 * kPi * mn / (ny * grid.dy);
      const double q = std::hypot(qx, qy);
      const double amp = std::pow(1.0 + qx * qx * ell_x * ell_x + qy * qy * ell_y * ell_y, -0.75) *
                         lambda_s_transmission(q, spec.lambda_s);
      // column n = 0 holds both m and -m: one draw, conjugated, keeps the field real
      const Complex xi = (mn == 0 && m < 0) ? std::conj(mode_noise(spec.seed, -m, 0))
                                            : mode_noise(spec.seed, m, mn);
      // phase of the grid's first cell centre, so that every grid samples the same
      // continuous surface at its own cell centres x_i = (i - (nx - 1) / 2) dx
      const double phase = qx * grid.x(0) + qy * grid.y(0);
      spectrum[static_cast<long>(ix) * nc + iy] = amp * xi * Complex(std::cos(phase), std::sin(phase));
    }
  }
  std::vector<double> z(n);
  fft.inverse(spectrum.data(), z.data(), nx);

  // standardise
  SurfaceStats st = calc_surface_stats(z);
  for (double& v : z) v = (v - st.mean) / st.rq;

  // Fleishman transform with targets corrected until the sample moments match
  const bool gaussian = spec.skewness == 0.0 && spec.kurtosis == 3.0;
  std::vector<double> y = z;
  if (!gaussian) {
    double t1 = spec.skewness, t2 = spec.kurtosis;
    for (int it = 0; it < 40; ++it) {
      double b, c, d;
      if (!solve_fleishman(t1, t2, b, c, d)) {
        std::snprintf(buf, sizeof buf,
                      "%s: skewness %g with kurtosis %g cannot be generated; the kurtosis must "
                      "exceed 1 + skewness^2 and stay within the power-transform range",
                      source.c_str(), spec.skewness, spec.kurtosis);
        throw InputError(buf);
      }
      for (long k = 0; k < n; ++k) y[k] = -c + z[k] * (b + z[k] * (c + z[k] * d));
      st = calc_surface_stats(y);
      const double e1 = spec.skewness - st.skewness, e2 = spec.kurtosis - st.kurtosis;
      if (std::abs(e1) <= 0.002 * std::max(1.0, std::abs(spec.skewness)) &&
          std::abs(e2) <= 0.002 * spec.kurtosis) {
        break;
      }
      t1 += e1;
      t2 += e2;
    }
  }
  st = calc_surface_stats(y);
  for (double& v : y) v = (v - st.mean) / st.rq * spec.rq;
  return y;
}

}  // namespace kneesim::particles
