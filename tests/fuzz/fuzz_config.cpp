// Fuzz harness: the TOML config reader (models::load_config through the toml++ adapter).
// Contract: any input either loads or throws kneesim::InputError; anything else (another
// exception, a crash, a sanitizer report) is a finding.
#include <cstddef>
#include <cstdint>

#include "engine/errors.h"
#include "models/config.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = kneesim::fuzz::write_input(data, size, ".toml");
  try {
    kneesim::models::load_config(file, {});
  } catch (const kneesim::InputError&) {
  }
  return 0;
}
