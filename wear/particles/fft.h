// The one adapter to a Fourier transform library for the particle BEM. Every convolution in
// wear/particles (surface deflection by DC-FFT, subsurface stress by frequency response,
// rough-surface filtering) goes through Fft2, so the backend is a build choice: Eigen's FFT
// module (kissfft, BSD) by default, FFTW3 when KNEESIM_WITH_FFTW is ON (GPL; off by default
// to keep the project BSD-licensed).
//
// Why a hand-written 2D transform from 1D row/column passes instead of a library 2D call:
// the BEM fields are zero-padded (only the first `rows_in` rows of the padded grid carry data)
// and only the first `rows_out` rows of the result are wanted, so skipping the zero rows on
// the forward pass and the discarded rows on the inverse pass saves about a quarter of the
// work. Rows and columns are transformed independently in OpenMP loops, so the result is
// bit-identical for any thread count.
#pragma once

#include <complex>
#include <memory>

namespace kneesim::particles {

using Complex = std::complex<double>;

// 2D real-to-complex transform of an nx-by-ny real field stored row-major (y fastest, index
// i * ny + j); the spectrum is nx-by-(ny/2 + 1), also row-major. ny must be even.
class Fft2 {
 public:
  Fft2(int nx, int ny);
  ~Fft2();
  Fft2(const Fft2&) = delete;
  Fft2& operator=(const Fft2&) = delete;

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int nyc() const { return ny_ / 2 + 1; }  // spectrum columns

  // forward transform; rows >= rows_in of `in` are taken as zero and not read
  void forward(const double* in, Complex* out, int rows_in) const;
  // unnormalised inverse (the result is nx * ny times the field); destroys `spectrum`;
  // writes only rows < rows_out of `out`
  void inverse(Complex* spectrum, double* out, int rows_out) const;

  // name of the compiled backend: "eigen-kissfft" or "fftw3"
  static const char* backend();

 private:
  struct Impl;
  int nx_, ny_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kneesim::particles
