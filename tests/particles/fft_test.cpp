// Reference: the direct discrete Fourier transform sum (O(n^2)), and the inverse of the
// forward transform (times nx * ny, the unnormalised convention of Fft2).
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "wear/particles/fft.h"

using namespace kneesim::particles;

TEST_CASE("Fft2 matches the direct DFT, skips zero rows and inverts") {
  const int nx = 12, ny = 8, rows_in = 9;
  Fft2 f(nx, ny);
  std::vector<double> in(nx * ny, 0.0), out(nx * ny);
  for (int k = 0; k < rows_in * ny; ++k) in[k] = std::sin(0.37 * k * k + 1.0);
  std::vector<Complex> s(nx * f.nyc());
  f.forward(in.data(), s.data(), rows_in);
  const double pi = 3.14159265358979323846;
  double err = 0.0;
  for (int kx = 0; kx < nx; ++kx)
    for (int ky = 0; ky < f.nyc(); ++ky) {
      Complex d(0.0, 0.0);
      for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j)
          d += in[i * ny + j] * std::polar(1.0, -2.0 * pi * (double(kx * i) / nx + double(ky * j) / ny));
      err = std::max(err, std::abs(d - s[kx * f.nyc() + ky]));
    }
  CHECK(err < 1e-12);
  f.inverse(s.data(), out.data(), nx);
  for (int k = 0; k < nx * ny; ++k) CHECK(out[k] / (nx * ny) == doctest::Approx(in[k]).epsilon(1e-12));
  CHECK_THROWS(Fft2(8, 7));  // odd ny is refused
}
