// Periodic waveforms: named channels over 0..100 % of the gait cycle (0 % = heel strike, one
// cycle per second in the ISO rigs), joined linearly (tables, measured data) or by half-cosine
// segments v0 + (v1 - v0) (1 - cos(pi s)) / 2 (key points, physics.md section 3). The engine's
// Model holds one (the rig's channels); loads/iso14243 reads them from files and fills it.
// Values stay in the units of the channel name (deg, mm, N, N*m); the engine converts to SI.
//
// Periodicity: the points of each channel are padded once at load time with their periodic
// images (the last point shifted by -100 %, the first by +100 %) so a lookup is one binary
// search over a short array, with no allocation and no branching on the ends. A channel with
// points at both 0 and 100 % whose values differ jumps at 100 % -> 0 % (measured data); we
// keep the data as given rather than silently editing it.
// Rejected: a uniform resampling grid (loses the exact key-point shape that the ISO 14243-3
// reproduction tests rely on) and splines (overshoot between sparse key points).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace kneesim::engine {

enum class Interpolation {
  linear,       // straight segments (tables, measured data)
  half_cosine,  // zero slope at every key point (ISO 14243-style key points)
};

class Waveform {
 public:
  // a table waveform from columns (pct strictly increasing in 0..100, every column the size of
  // pct); `source` names the origin in messages; throws InputError on violations
  static Waveform from_table(const std::vector<std::string>& names, const std::vector<double>& pct,
                             const std::vector<std::vector<double>>& columns,
                             const std::string& source = "<table>");

  // one channel of key points joined by half-cosine segments (for code-built waveforms)
  struct KeyPoints {
    std::string name;           // channel name with unit suffix, e.g. "flexion_deg"
    std::vector<double> pct;    // [% of gait cycle], strictly increasing in 0..100, n >= 2
    std::vector<double> value;  // [channel unit], n
  };
  static Waveform from_keypoints(const std::vector<KeyPoints>& channels,
                                 const std::string& source = "<keypoints>");

  int channel(std::string_view name) const;  // index, or -1 when absent
  int channel_count() const { return static_cast<int>(channels_.size()); }
  std::vector<std::string> channel_names() const;
  const std::string& channel_name(int channel) const { return channels_[channel].name; }
  Interpolation interpolation(int channel) const { return channels_[channel].interp; }
  const std::string& source() const { return source_; }

  // value at any gait_pct (wrapped modulo 100); allocation-free
  double value(int channel, double gait_pct) const;
  // d value / d gait_pct [channel unit per %]; allocation-free
  double derivative(int channel, double gait_pct) const;

  // the defining points of a channel, without the periodic padding
  std::vector<double> points_pct(int channel) const;
  std::vector<double> points_value(int channel) const;

  // multiplies a channel by a factor (sign conventions, unit changes)
  void scale_channel(int channel, double factor);

  // every channel of `other` (points and interpolation as they are) replaces the channel of
  // the same name in place, keeping channel indices, or is appended
  void merge(const Waveform& other);

 private:
  struct Channel {
    std::string name;       // with unit suffix
    Interpolation interp;   // segment shape
    std::vector<double> t;  // [%], strictly increasing, padded so t.front() <= 0, t.back() >= 100
    std::vector<double> v;  // [channel unit], t.size()
    int first = 0;          // index of the first defining (unpadded) point
    int count = 0;          // number of defining points
  };
  void add_channel(const std::string& name, Interpolation interp, const std::vector<double>& t,
                   const std::vector<double>& v);
  std::size_t segment(const Channel& c, double p) const;

  std::vector<Channel> channels_;
  std::string source_;
};

// half-cosine blend from (t0, v0) to (t1, v1) evaluated at t (t0 <= t <= t1)
double half_cosine(double t0, double v0, double t1, double v1, double t);

}  // namespace kneesim::engine
