// Fuzz harness: mesh import (models::load_mesh through assimp). The first byte picks the
// format by extension (STL, OBJ, PLY); the rest is the file. Contract: load or InputError.
#include <cstddef>
#include <cstdint>

#include "engine/errors.h"
#include "models/mesh_io.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const char* ext[] = {".stl", ".obj", ".ply"};
  const auto file = kneesim::fuzz::write_input(data + 1, size - 1, ext[data[0] % 3]);
  kneesim::models::MeshImportOptions o;
  o.require_closed = (data[0] / 3) % 2 == 1;
  try {
    kneesim::models::load_mesh(file, o);
  } catch (const kneesim::InputError&) {
  }
  return 0;
}
