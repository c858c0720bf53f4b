#include "loads/iso14243/lowpass.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kneesim::loads {
namespace {

// one forward pass of the second-order Butterworth filter (Winter 2009, eq. 3.18: the
// recursive coefficients from the bilinear transform, C the correction of the cutoff for the
// number of passes)
std::vector<double> butterworth_pass(const std::vector<double>& x, double fs, double fc) {
  constexpr double kTwoPassCorrection = 0.802;
  const double wc = std::tan(std::numbers::pi * fc / fs) / kTwoPassCorrection;
  const double k1 = std::sqrt(2.0) * wc, k2 = wc * wc;
  const double a0 = k2 / (1.0 + k1 + k2), a1 = 2.0 * a0, a2 = a0;
  const double k3 = 2.0 * a0 / k2;
  const double b1 = -2.0 * a0 + k3, b2 = 1.0 - 2.0 * a0 - k3;
  std::vector<double> y(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    const double x1 = i >= 1 ? x[i - 1] : x[0], x2 = i >= 2 ? x[i - 2] : x[0];
    const double y1 = i >= 1 ? y[i - 1] : x[0], y2 = i >= 2 ? y[i - 2] : x[0];
    y[i] = a0 * x[i] + a1 * x1 + a2 * x2 + b1 * y1 + b2 * y2;
  }
  return y;
}

}  // namespace

std::vector<double> lowpass(const std::vector<double>& x, double fs, double fc) {
  const size_t n = x.size();
  if (n < 3 || !(fc > 0.0) || !(fc < 0.5 * fs)) return x;
  // odd reflection about each end, about three time constants of the filter long
  const size_t pad = std::min(n - 1, static_cast<size_t>(std::ceil(3.0 * fs / fc)));
  std::vector<double> ext;
  ext.reserve(n + 2 * pad);
  for (size_t i = pad; i >= 1; --i) ext.push_back(2.0 * x.front() - x[i]);
  ext.insert(ext.end(), x.begin(), x.end());
  for (size_t i = 1; i <= pad; ++i) ext.push_back(2.0 * x.back() - x[n - 1 - i]);
  std::vector<double> y = butterworth_pass(ext, fs, fc);
  std::reverse(y.begin(), y.end());
  y = butterworth_pass(y, fs, fc);
  std::reverse(y.begin(), y.end());
  return std::vector<double>(y.begin() + static_cast<long>(pad), y.begin() + static_cast<long>(pad + n));
}

CutoffChoice residual_analysis_cutoff(const std::vector<double>& x, double fs) {
  std::vector<double> fc, r;
  for (double f = 0.5; f <= 0.45 * fs; f += 0.25) {
    const std::vector<double> y = lowpass(x, fs, f);
    double ss = 0.0;
    for (size_t i = 0; i < x.size(); ++i) ss += (x[i] - y[i]) * (x[i] - y[i]);
    fc.push_back(f);
    r.push_back(std::sqrt(ss / static_cast<double>(x.size())));
  }
  CutoffChoice out;
  if (fc.size() < 6) return out;
  // the noise line over the upper third of the cutoffs
  const size_t from = 2 * fc.size() / 3;
  double s1 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = from; i < fc.size(); ++i) {
    s1 += 1, sx += fc[i], sy += r[i], sxx += fc[i] * fc[i], sxy += fc[i] * r[i];
  }
  const double slope = (s1 * sxy - sx * sy) / (s1 * sxx - sx * sx);
  out.noise_rms = std::max(0.0, (sy - slope * sx) / s1);
  // the lowest cutoff whose residual has fallen to the noise estimate
  out.cutoff_Hz = fc.back();
  for (size_t i = 0; i < fc.size(); ++i) {
    if (r[i] <= out.noise_rms) {
      out.cutoff_Hz = fc[i];
      break;
    }
  }
  return out;
}

}  // namespace kneesim::loads
