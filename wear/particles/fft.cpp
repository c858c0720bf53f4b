#include "wear/particles/fft.h"

#include <omp.h>

#include <mutex>
#include <stdexcept>
#include <vector>

#ifdef KNEESIM_USE_FFTW
#include <fftw3.h>
#else
#include <unsupported/Eigen/FFT>
#endif

namespace kneesim::particles {

#ifdef KNEESIM_USE_FFTW

// FFTW plans are made once (the planner is not thread-safe, hence the mutex) and executed
// from every thread through the new-array interface, which is thread-safe.
struct Fft2::Impl {
  fftw_plan r2c = nullptr, c2r = nullptr, fwd = nullptr, bwd = nullptr;
  Impl(int nx, int ny) {
    static std::mutex planner;
    std::lock_guard<std::mutex> lock(planner);
    std::vector<double> r(ny);
    std::vector<Complex> c(ny / 2 + 1), cx(nx), cy(nx);
    auto* pc = reinterpret_cast<fftw_complex*>(c.data());
    auto* px = reinterpret_cast<fftw_complex*>(cx.data());
    auto* py = reinterpret_cast<fftw_complex*>(cy.data());
    const unsigned flags = FFTW_ESTIMATE | FFTW_UNALIGNED;
    r2c = fftw_plan_dft_r2c_1d(ny, r.data(), pc, flags);
    c2r = fftw_plan_dft_c2r_1d(ny, pc, r.data(), flags);
    fwd = fftw_plan_dft_1d(nx, px, py, FFTW_FORWARD, flags);
    bwd = fftw_plan_dft_1d(nx, px, py, FFTW_BACKWARD, flags);
  }
  ~Impl() {
    fftw_destroy_plan(r2c);
    fftw_destroy_plan(c2r);
    fftw_destroy_plan(fwd);
    fftw_destroy_plan(bwd);
  }
  struct Local {};
  static fftw_complex* fc(Complex* p) { return reinterpret_cast<fftw_complex*>(p); }
  void row_forward(Local&, Complex* dst, const double* src, int) const {
    fftw_execute_dft_r2c(r2c, const_cast<double*>(src), fc(dst));
  }
  void row_inverse(Local&, double* dst, Complex* src, int) const {
    fftw_execute_dft_c2r(c2r, fc(src), dst);  // destroys src, which is scratch
  }
  void col(Local&, Complex* dst, Complex* src, int, bool inverse) const {
    fftw_execute_dft(inverse ? bwd : fwd, fc(src), fc(dst));
  }
};
const char* Fft2::backend() { return "fftw3"; }

#else

// kissfft keeps plans and scratch inside the FFT object, so every thread uses its own.
struct Fft2::Impl {
  Impl(int, int) {}
  struct Local {
    Eigen::FFT<double> fft;
    Local() {
      fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
      fft.SetFlag(Eigen::FFT<double>::Unscaled);
    }
  };
  void row_forward(Local& l, Complex* dst, const double* src, int n) const {
    l.fft.fwd(dst, src, n);
  }
  void row_inverse(Local& l, double* dst, Complex* src, int n) const { l.fft.inv(dst, src, n); }
  void col(Local& l, Complex* dst, Complex* src, int n, bool inverse) const {
    if (inverse) {
      l.fft.inv(dst, src, n);
    } else {
      l.fft.fwd(dst, src, n);
    }
  }
};
const char* Fft2::backend() { return "eigen-kissfft"; }

#endif

Fft2::Fft2(int nx, int ny) : nx_(nx), ny_(ny) {
  if (nx < 2 || ny < 2 || ny % 2 != 0) {
    throw std::invalid_argument("Fft2 needs nx >= 2 and an even ny >= 2");
  }
  impl_ = std::make_unique<Impl>(nx, ny);
}

Fft2::~Fft2() = default;

void Fft2::forward(const double* in, Complex* out, int rows_in) const {
  const int nx = nx_, ny = ny_, nc = nyc();
#pragma omp parallel
  {
    Impl::Local local;
    std::vector<double> row(ny);
    std::vector<Complex> a(nx), b(nx);
    // real transforms of the rows that carry data; the padding rows transform to zero
#pragma omp for schedule(static)
    for (int i = 0; i < nx; ++i) {
      Complex* dst = out + static_cast<long>(i) * nc;
      if (i < rows_in) {
        std::copy(in + static_cast<long>(i) * ny, in + static_cast<long>(i + 1) * ny, row.begin());
        impl_->row_forward(local, dst, row.data(), ny);
      } else {
        std::fill(dst, dst + nc, Complex(0.0, 0.0));
      }
    }
    // complex transforms down the columns
#pragma omp for schedule(static)
    for (int j = 0; j < nc; ++j) {
      for (int i = 0; i < nx; ++i) a[i] = out[static_cast<long>(i) * nc + j];
      impl_->col(local, b.data(), a.data(), nx, false);
      for (int i = 0; i < nx; ++i) out[static_cast<long>(i) * nc + j] = b[i];
    }
  }
}

void Fft2::inverse(Complex* spectrum, double* out, int rows_out) const {
  const int nx = nx_, ny = ny_, nc = nyc();
#pragma omp parallel
  {
    Impl::Local local;
    std::vector<Complex> a(nx), b(nx), row(nc);
    std::vector<double> r(ny);
    // inverse complex transforms down the columns
#pragma omp for schedule(static)
    for (int j = 0; j < nc; ++j) {
      for (int i = 0; i < nx; ++i) a[i] = spectrum[static_cast<long>(i) * nc + j];
      impl_->col(local, b.data(), a.data(), nx, true);
      for (int i = 0; i < nx; ++i) spectrum[static_cast<long>(i) * nc + j] = b[i];
    }
    // complex-to-real transforms of the wanted rows only
#pragma omp for schedule(static)
    for (int i = 0; i < rows_out; ++i) {
      const Complex* src = spectrum + static_cast<long>(i) * nc;
      std::copy(src, src + nc, row.begin());
      impl_->row_inverse(local, r.data(), row.data(), ny);
      std::copy(r.begin(), r.end(), out + static_cast<long>(i) * ny);
    }
  }
}

}  // namespace kneesim::particles
