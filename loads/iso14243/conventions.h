// Sign and side conventions of a waveform file, applied once after loading. Published work
// disagrees on the AP and IE directions (physics.md section 3, Wang 2018), so they are
// configuration rather than code.
//
// Channels are recognised by the prefix of their name: `ap_` (anterior-posterior force or
// displacement), `ie_` (internal-external torque or rotation), `ml_` (medial-lateral) and
// `vv_` (varus-valgus). Other channels (flexion_deg, axial_force_N, ...) are never changed.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "loads/iso14243/waveform.h"

namespace kneesim::loads {

struct WaveformConventions {
  double ap_sign = 1.0;  // multiplies every `ap_` channel; -1 when the file has + posterior [-]
  double ie_sign = 1.0;  // multiplies every `ie_` channel; -1 when the file has + external [-]
  // true when the file's channels are components in a LEFT knee's axes that keep the
  // OpenSim-like global directions (+z to the subject's right, i.e. medial for a left knee).
  // The data is mirrored into the project's right knee (z -> -z): `ml_`, `ie_` and `vv_`
  // channels change sign (rotations about x and y and translations along z flip under the
  // mirror; flexion about z and AP/axial channels do not). Leave false for files that already
  // use anatomical signs (+ internal, + varus, + lateral), which are the same for either knee.
  bool left_knee = false;  // [-]
};

// the waveform with the conventions applied (mirror first, then the AP and IE signs)
Waveform apply_conventions(const Waveform& w, const WaveformConventions& conventions);

// the waveform with the channels named in `delays` delayed by their value [% of the cycle]
// (the delayed channel at p is the original at p - delay, periodic); when any delay is nonzero
// every channel is resampled into a table every 0.1 % (linear between samples), else `w` is
// returned unchanged. For load-timing candidates (a load pattern whose phase differs from the
// measured flexion's) and the `gait.*_shift_pct` config keys.
Waveform delay_channels(const Waveform& w, const std::vector<std::pair<std::string, double>>& delays);

}  // namespace kneesim::loads
