// JSON summaries, written atomically with stable key order (nlohmann::json sorts keys).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

namespace kneesim::io {

void write_json(const std::filesystem::path& path, const nlohmann::json& j);

}  // namespace kneesim::io
