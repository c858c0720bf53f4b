// Fuzz harness: the gait tables. The first byte picks the reader: the waveform file
// (loads::load_waveform, CSV table or key points) or the measured kinematics (CSV or OpenSim
// .sto, loads::read_kinematics). Contract: load or InputError.
#include <cstddef>
#include <cstdint>

#include "engine/errors.h"
#include "loads/iso14243/kinematics.h"
#include "loads/iso14243/waveform.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const int variant = data[0] % 3;
  const auto file = kneesim::fuzz::write_input(data + 1, size - 1, variant == 2 ? ".sto" : ".csv");
  try {
    if (variant == 0) {
      kneesim::loads::load_waveform(file);
    } else {
      kneesim::loads::to_waveform(kneesim::loads::read_kinematics(file));
    }
  } catch (const kneesim::InputError&) {
  }
  return 0;
}
