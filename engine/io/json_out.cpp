#include "engine/io/json_out.h"

#include "engine/io/atomic_file.h"

namespace kneesim::io {

void write_json(const std::filesystem::path& path, const nlohmann::json& j) {
  write_file_atomic(path, j.dump(2) + "\n");
}

}  // namespace kneesim::io
