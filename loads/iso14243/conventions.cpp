#include "loads/iso14243/conventions.h"

#include <string>

namespace kneesim::loads {
namespace {

bool has_prefix(const std::string& name, const char* prefix) { return name.rfind(prefix, 0) == 0; }

}  // namespace

Waveform apply_conventions(const Waveform& w, const WaveformConventions& conventions) {
  Waveform out = w;
  for (int c = 0; c < out.channel_count(); ++c) {
    const std::string& name = out.channel_name(c);
    double factor = 1.0;
    // mirror a left knee into the right-knee frame
    if (conventions.left_knee &&
        (has_prefix(name, "ml_") || has_prefix(name, "ie_") || has_prefix(name, "vv_"))) {
      factor = -factor;
    }
    // then the file's sign choices
    if (has_prefix(name, "ap_")) factor *= conventions.ap_sign;
    if (has_prefix(name, "ie_")) factor *= conventions.ie_sign;
    if (factor != 1.0) out.scale_channel(c, factor);
  }
  return out;
}

Waveform delay_channels(const Waveform& w,
                        const std::vector<std::pair<std::string, double>>& delays) {
  bool any = false;
  for (const auto& [name, d] : delays) any = any || d != 0.0;
  if (!any) return w;
  constexpr int kSamples = 1000;  // every 0.1 %
  std::vector<double> pct(kSamples + 1);
  for (int i = 0; i <= kSamples; ++i) pct[static_cast<size_t>(i)] = 100.0 * i / kSamples;
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  for (int c = 0; c < w.channel_count(); ++c) {
    double delay = 0.0;
    for (const auto& [name, d] : delays) {
      if (name == w.channel_name(c)) delay = d;
    }
    std::vector<double> col(pct.size());
    for (size_t i = 0; i < pct.size(); ++i) col[i] = w.value(c, pct[i] - delay);
    names.push_back(w.channel_name(c));
    columns.push_back(std::move(col));
  }
  return Waveform::from_table(names, pct, columns, w.source() + " (delayed channels)");
}

}  // namespace kneesim::loads
