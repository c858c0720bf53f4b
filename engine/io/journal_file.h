// Journals: files that grow one line at a time and must survive a kill at any instant (the
// finished trials of a study). A line goes out with one write(2) on an O_APPEND descriptor and
// is fsync'ed, so a killed writer leaves whole lines and at most one torn last line without its
// newline, which the readers of such journals drop.
#pragma once

#include <filesystem>
#include <string_view>

namespace kneesim::io {

// appends `line` (newline-terminated); throws std::runtime_error naming the path on failure
void append_line_durable(const std::filesystem::path& path, std::string_view line);

}  // namespace kneesim::io
