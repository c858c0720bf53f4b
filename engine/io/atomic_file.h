// Results are written atomically: content goes to a temporary file in the same folder, is
// flushed and fsync'ed, then renamed over the target. A killed run therefore leaves either the
// previous complete file or none, never a half-written file that looks complete.
#pragma once

#include <filesystem>
#include <string_view>

namespace kneesim::io {

// writes `content` to `path` atomically; creates parent folders; throws std::runtime_error
// naming the path on failure
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

// reads a whole file; throws std::runtime_error naming the path when it cannot be read
std::string read_file(const std::filesystem::path& path);

}  // namespace kneesim::io
