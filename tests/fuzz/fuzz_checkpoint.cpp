// Fuzz harness: the wear checkpoint reader (wear::read_checkpoint). A random file almost never
// starts with the magic and carries a matching FNV-1a content hash, so the input is the body
// after the 16-byte magic: the harness prepends the magic, appends the correct hash and expects
// the identity stored in the file, and the fuzzer reaches the body parser (counts, arrays,
// frames). An input whose first byte is odd is written as it is instead (the header checks).
// Contract: read or InputError.
#include <cstddef>
#include <cstdint>
#include <algorithm>
#include <cstring>
#include <vector>

#include "engine/errors.h"
#include "tests/fuzz/fuzz_input.h"
#include "wear/checkpoint.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  std::vector<std::uint8_t> bytes;
  std::uint64_t identity = 0;
  if (data[0] % 2 == 1) {
    bytes.assign(data + 1, data + size);
  } else {
    const char magic[16] = "kneesim-wear-v3";
    bytes.assign(magic, magic + sizeof magic);
    bytes.insert(bytes.end(), data + 1, data + size);
    const std::uint64_t h = kneesim::wear::fnv1a(bytes.data(), bytes.size());
    const auto* hb = reinterpret_cast<const std::uint8_t*>(&h);
    bytes.insert(bytes.end(), hb, hb + 8);
    std::memcpy(&identity, bytes.data() + 16, std::min<std::size_t>(8, size - 1));
  }
  const auto file = kneesim::fuzz::write_input(bytes.data(), bytes.size(), ".checkpoint");
  try {
    kneesim::wear::read_checkpoint(file, identity);
  } catch (const kneesim::InputError&) {
  }
  return 0;
}
