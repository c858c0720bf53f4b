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

}  // namespace kneesim::loads
