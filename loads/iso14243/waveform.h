// Gait waveform files (loads/iso14243/README.md), read into the engine's periodic waveform
// (engine/waveform.h). Two file forms:
//   table      `gait_pct,<channel>,...` rows, joined linearly;
//   keypoints  `# form: keypoints` and rows `channel,gait_pct,value`, joined by half-cosine
//              segments v0 + (v1 - v0) (1 - cos(pi s)) / 2 (physics.md section 3).
#pragma once

#include <filesystem>

#include "engine/waveform.h"

namespace kneesim::loads {

using engine::half_cosine;
using engine::Interpolation;
using engine::Waveform;

// reads either form; throws InputError naming the file (and line/column) for a missing file,
// non-numeric cells, ragged rows, non-increasing gait_pct, gait_pct outside 0..100, fewer than
// 2 points per channel, duplicate channel names or an unknown form
Waveform load_waveform(const std::filesystem::path& file);

}  // namespace kneesim::loads
