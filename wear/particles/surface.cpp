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

// standard normal samples by Box-Muller on a 64-bit Mersenne twister (portable, seeded)
std::vector<double> white_noise(long n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<double> out(n);
  const double scale = 1.0 / 18446744073709551616.0;  // 2^-64
  for (long k = 0; k < n; k += 2) {
    const double u1 = (static_cast<double>(rng()) + 0.5) * scale;
    const double u2 = (static_cast<double>(rng()) + 0.5) * scale;
    const double r = std::sqrt(-2.0 * std::log(u1));
    out[k] = r * std::cos(2.0 * kPi * u2);
    if (k + 1 < n) out[k + 1] = r * std::sin(2.0 * kPi * u2);
  }
  return out;
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

std::vector<double> make_rough_surface(const Grid& grid, const SurfaceSpec& spec,
                                       const std::string& source) {
  char buf[256];
  if (!(spec.rq > 0.0) || !(spec.correlation_length > 0.0)) {
    std::snprintf(buf, sizeof buf,
                  "%s: roughness Rq = %g nm and correlation length = %g nm are not allowed; both "
                  "must be > 0",
                  source.c_str(), spec.rq * 1e9, spec.correlation_length * 1e9);
    throw InputError(buf);
  }
  const int nx = grid.nx, ny = grid.ny;
  const long n = grid.size();
  Fft2 fft(nx, ny);
  const int nc = fft.nyc();

  // filter: square root of the power spectrum of the exponential autocorrelation
  std::vector<double> acf(n);
  for (int i = 0; i < nx; ++i) {
    const double tx = (i <= nx / 2 ? i : i - nx) * grid.dx;
    for (int j = 0; j < ny; ++j) {
      const double ty = (j <= ny / 2 ? j : j - ny) * grid.dy;
      acf[static_cast<long>(i) * ny + j] =
          std::exp(-2.3 * std::hypot(tx, ty) / spec.correlation_length);
    }
  }
  std::vector<Complex> filt(static_cast<long>(nx) * nc), noise_hat(filt.size());
  fft.forward(acf.data(), filt.data(), nx);
  std::vector<double> noise = white_noise(n, spec.seed);
  fft.forward(noise.data(), noise_hat.data(), nx);
  for (std::size_t k = 0; k < filt.size(); ++k) {
    noise_hat[k] *= std::sqrt(std::max(filt[k].real(), 0.0));
  }
  noise_hat[0] = 0.0;  // zero mean
  std::vector<double> z(n);
  fft.inverse(noise_hat.data(), z.data(), nx);

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
