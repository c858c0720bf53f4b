#include "engine/waveform.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "engine/errors.h"

namespace kneesim::engine {
namespace {

constexpr double kCycle = 100.0;  // [%] period

double wrap_pct(double p) {
  double w = p - kCycle * std::floor(p / kCycle);
  return w >= kCycle ? 0.0 : w;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

double half_cosine(double t0, double v0, double t1, double v1, double t) {
  const double s = (t - t0) / (t1 - t0);
  return v0 + (v1 - v0) * 0.5 * (1.0 - std::cos(std::numbers::pi * s));
}

Waveform Waveform::from_table(const std::vector<std::string>& names, const std::vector<double>& pct,
                              const std::vector<std::vector<double>>& columns,
                              const std::string& source) {
  Waveform w;
  w.source_ = source;
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (columns.size() != names.size() || columns[c].size() != pct.size()) {
      throw InputError(source + ": column '" + names[c] +
                       "' has a different length from gait_pct.");
    }
    w.add_channel(names[c], Interpolation::linear, pct, columns[c]);
  }
  return w;
}

Waveform Waveform::from_keypoints(const std::vector<KeyPoints>& channels,
                                  const std::string& source) {
  Waveform w;
  w.source_ = source;
  for (const KeyPoints& k : channels) {
    if (k.value.size() != k.pct.size()) {
      throw InputError(source + ": channel '" + k.name + "' has " + std::to_string(k.pct.size()) +
                       " times but " + std::to_string(k.value.size()) + " values.");
    }
    w.add_channel(k.name, Interpolation::half_cosine, k.pct, k.value);
  }
  return w;
}

void Waveform::merge(const Waveform& other) {
  for (const Channel& c : other.channels_) {
    const int i = channel(c.name);
    if (i >= 0) {
      channels_[static_cast<std::size_t>(i)] = c;
    } else {
      channels_.push_back(c);
    }
  }
  source_ += " + " + other.source_;
}

void Waveform::add_channel(const std::string& name, Interpolation interp,
                           const std::vector<double>& t, const std::vector<double>& v) {
  if (channel(name) >= 0) {
    throw InputError(source_ + ": channel '" + name + "' appears twice.");
  }
  if (t.size() < 2) {
    throw InputError(source_ + ": channel '" + name + "' has " + std::to_string(t.size()) +
                     " point(s); at least 2 are needed.");
  }
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!(t[i] >= 0.0 && t[i] <= kCycle)) {
      throw InputError(source_ + ": channel '" + name + "' gait_pct " + fmt(t[i]) +
                       " is outside the allowed range 0..100 %.");
    }
    if (i > 0 && t[i] <= t[i - 1]) {
      throw InputError(source_ + ": channel '" + name + "' gait_pct " + fmt(t[i]) +
                       " does not increase over " + fmt(t[i - 1]) + ".");
    }
  }
  Channel c;
  c.name = name;
  c.interp = interp;
  // pad with the periodic images of the last and first points
  if (t.front() > 0.0) {
    c.t.push_back(t.back() - kCycle);
    c.v.push_back(v.back());
  }
  c.first = static_cast<int>(c.t.size());
  c.count = static_cast<int>(t.size());
  c.t.insert(c.t.end(), t.begin(), t.end());
  c.v.insert(c.v.end(), v.begin(), v.end());
  if (t.back() < kCycle) {
    c.t.push_back(t.front() + kCycle);
    c.v.push_back(v.front());
  }
  channels_.push_back(std::move(c));
}

int Waveform::channel(std::string_view name) const {
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    if (channels_[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

std::vector<std::string> Waveform::channel_names() const {
  std::vector<std::string> out;
  for (const Channel& c : channels_) out.push_back(c.name);
  return out;
}

std::vector<double> Waveform::points_pct(int ch) const {
  const Channel& c = channels_[ch];
  return {c.t.begin() + c.first, c.t.begin() + c.first + c.count};
}

std::vector<double> Waveform::points_value(int ch) const {
  const Channel& c = channels_[ch];
  return {c.v.begin() + c.first, c.v.begin() + c.first + c.count};
}

void Waveform::scale_channel(int ch, double factor) {
  for (double& x : channels_[ch].v) x *= factor;
}

// index i with t[i] <= p < t[i+1] (p already wrapped to [0, 100))
std::size_t Waveform::segment(const Channel& c, double p) const {
  auto it = std::upper_bound(c.t.begin(), c.t.end(), p);
  std::size_t i = static_cast<std::size_t>(it - c.t.begin());
  i = i == 0 ? 0 : i - 1;
  return std::min(i, c.t.size() - 2);
}

double Waveform::value(int ch, double gait_pct) const {
  const Channel& c = channels_[ch];
  const double p = wrap_pct(gait_pct);
  const std::size_t i = segment(c, p);
  const double t0 = c.t[i], t1 = c.t[i + 1], v0 = c.v[i], v1 = c.v[i + 1];
  switch (c.interp) {
    case Interpolation::linear:
      return v0 + (v1 - v0) * (p - t0) / (t1 - t0);
    case Interpolation::half_cosine:
      return half_cosine(t0, v0, t1, v1, p);
  }
  return 0.0;
}

double Waveform::derivative(int ch, double gait_pct) const {
  const Channel& c = channels_[ch];
  const double p = wrap_pct(gait_pct);
  const std::size_t i = segment(c, p);
  const double t0 = c.t[i], t1 = c.t[i + 1], v0 = c.v[i], v1 = c.v[i + 1];
  switch (c.interp) {
    case Interpolation::linear:
      return (v1 - v0) / (t1 - t0);
    case Interpolation::half_cosine:
      return (v1 - v0) * 0.5 * std::numbers::pi / (t1 - t0) *
             std::sin(std::numbers::pi * (p - t0) / (t1 - t0));
  }
  return 0.0;
}

}  // namespace kneesim::engine
