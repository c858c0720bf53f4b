#include "engine/io/source_tree.h"

#include <cstdlib>

namespace kneesim::io {

std::filesystem::path source_dir() { return KNEESIM_SOURCE_TREE; }

std::filesystem::path plots_dir() {
  if (const char* env = std::getenv("KNEESIM_PLOTS_DIR")) return env;
  return source_dir() / "tools/plots";
}

}  // namespace kneesim::io
