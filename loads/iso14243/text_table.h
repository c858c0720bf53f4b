// Small delimited-text reader shared by the waveform and kinematics loaders. It keeps cells as
// strings with their file line numbers, so every error can name the file, line and column.
// Full-line comments start with '#'; a comment of the form `# key: value` is kept as a
// directive (e.g. `# form: keypoints`). OpenSim .sto files are read by skipping everything up
// to the `endheader` line. We did not use a general CSV library: quoting and embedded
// delimiters never occur in numeric gait tables, and a hand-written reader gives exact messages.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace kneesim::loads {

struct TextTable {
  std::filesystem::path file;                     // where it was read from
  std::vector<std::string> header;                // column names, trimmed
  std::vector<std::vector<std::string>> cells;    // rows x header.size(), trimmed
  std::vector<int> line;                          // 1-based file line of each row, rows
  std::map<std::string, std::string> directives;  // `# key: value` comments, lower-case keys

  int column(const std::string& name) const;  // index of a header name, -1 if absent
  // the number in a cell; throws InputError naming file, line, column and the text when it is
  // not a finite number
  double number(std::size_t row, std::size_t col) const;
};

enum class TextFormat {
  csv,  // comma-separated, '#' comments
  sto,  // OpenSim storage: header block up to `endheader`, then tab-separated columns
};

// reads a whole table; throws InputError for a missing or unreadable file, an empty file, and
// ragged rows (naming the line and the cell counts)
TextTable read_text_table(const std::filesystem::path& file, TextFormat format);

// removes a leading UTF-8 byte-order mark (EF BB BF), which spreadsheets write at the start of
// "CSV UTF-8" files; true when one was removed. Readers call it on the first line only.
bool strip_utf8_bom(std::string& first_line);

// Why a data row of a comma-separated table has `row_cells` cells against the header's
// `header_cells`, when its text shows a likely cause: another separator (';', tab, '|') with
// decimal commas, or more cells than the header's (a decimal comma splits 0,5 in two). Returns a
// parenthesised clause to append to the message, or "" when the text shows neither.
std::string separator_hint(const std::string& header_line, const std::string& row_line,
                           std::size_t header_cells, std::size_t row_cells);

// " (a decimal comma? write 0.5)" when `text` is a number written with a decimal comma,
// otherwise ""
std::string decimal_comma_hint(const std::string& text);

// a path as it should appear in messages
std::string display_path(const std::filesystem::path& file);

}  // namespace kneesim::loads
