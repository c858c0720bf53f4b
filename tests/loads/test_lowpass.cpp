// The zero-lag Butterworth low-pass and Winter's residual analysis (loads/iso14243/lowpass.h).
// References: the two passes of a second-order Butterworth filter with the 0.802 cutoff
// correction attenuate a sine at the cutoff by 3 dB (gain 1/sqrt(2)) and fall off as a fourth
// order beyond it (gain (fc/f)^4 far above the cutoff), with no phase lag; residual analysis on
// a band-limited signal plus white noise recovers the noise RMS (tolerance 20 %: the residual
// line's intercept is an estimate) and puts the cutoff above the signal's band.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "loads/iso14243/lowpass.h"

using namespace kneesim::loads;

namespace {

// amplitude and lag (samples) of the filtered sine of frequency f in the middle of a long record
std::pair<double, double> response(double f, double fs, double fc) {
  const int n = 4000;
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) x[static_cast<size_t>(i)] = std::sin(2.0 * std::numbers::pi * f * i / fs);
  const std::vector<double> y = lowpass(x, fs, fc);
  double sxy = 0, sxx = 0, syy = 0;
  for (int i = n / 4; i < 3 * n / 4; ++i) {
    sxy += x[static_cast<size_t>(i)] * y[static_cast<size_t>(i)];
    sxx += x[static_cast<size_t>(i)] * x[static_cast<size_t>(i)];
    syy += y[static_cast<size_t>(i)] * y[static_cast<size_t>(i)];
  }
  return {std::sqrt(syy / sxx), sxy / std::sqrt(sxx * syy)};  // gain, correlation (1: no lag)
}

}  // namespace

TEST_CASE("zero-lag Butterworth: -3 dB at the cutoff, fourth-order fall-off, no lag") {
  const double fs = 120.0, fc = 8.0;
  const auto at_cut = response(fc, fs, fc);
  CHECK(at_cut.first == doctest::Approx(1.0 / std::sqrt(2.0)).epsilon(0.03));
  CHECK(at_cut.second == doctest::Approx(1.0).epsilon(1e-6));
  CHECK(response(fc / 5.0, fs, fc).first == doctest::Approx(1.0).epsilon(0.01));
  const auto high = response(4.0 * fc, fs, fc);
  CHECK(high.first < 2.0 * std::pow(0.25, 4) * 1.5);
  // the ends: a constant passes unchanged
  const std::vector<double> c(50, 3.5);
  for (double v : lowpass(c, fs, fc)) CHECK(v == doctest::Approx(3.5));
}

TEST_CASE("residual analysis recovers the noise and cuts above the signal's band") {
  const double fs = 120.0, sigma = 15.0;
  std::mt19937_64 rng(4);
  std::normal_distribution<double> z(0.0, sigma);
  std::vector<double> x(300);
  for (size_t i = 0; i < x.size(); ++i) {
    const double t = static_cast<double>(i) / fs;
    x[i] = 800.0 * std::sin(2.0 * std::numbers::pi * 1.0 * t) +
           300.0 * std::sin(2.0 * std::numbers::pi * 3.0 * t + 0.4) +
           100.0 * std::sin(2.0 * std::numbers::pi * 5.0 * t + 1.1) + z(rng);
  }
  const CutoffChoice c = residual_analysis_cutoff(x, fs);
  CHECK(c.noise_rms == doctest::Approx(sigma).epsilon(0.2));
  CHECK(c.cutoff_Hz > 5.0);
  CHECK(c.cutoff_Hz < 0.25 * fs);
}
