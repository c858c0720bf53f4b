// Fuzz harness: the measured-data readers of `kneesim diagnose`. The first byte picks the
// reader: block-on-ring wear, knee wear, measured kinematics (CSV or .sto). The block-on-ring
// table also goes through make_bor_case, whose validation needs no simulation. Contract: read
// or InputError.
#include <cstddef>
#include <cstdint>

#include "analysis/diagnosis/bor_case.h"
#include "analysis/diagnosis/kinematics_case.h"
#include "analysis/diagnosis/knee_wear_case.h"
#include "engine/errors.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const int variant = data[0] % 4;
  const auto file =
      kneesim::fuzz::write_input(data + 1, size - 1, variant == 3 ? ".sto" : ".csv");
  try {
    switch (variant) {
      case 0: kneesim::diagnosis::read_bor_measured(file.string()); break;
      case 1: kneesim::diagnosis::read_knee_wear_measured(file.string()); break;
      default:
        kneesim::diagnosis::read_kinematics_measured(file.string(), Eigen::Vector3d::Zero());
    }
  } catch (const kneesim::InputError&) {
  }
  return 0;
}
