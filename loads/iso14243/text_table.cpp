#include "loads/iso14243/text_table.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "engine/errors.h"

namespace kneesim::loads {
namespace {

std::string trim(std::string_view s) {
  std::size_t b = 0;
  std::size_t e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return std::string(s.substr(b, e - b));
}

std::vector<std::string> split(const std::string& s, char delimiter) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    std::size_t pos = s.find(delimiter, start);
    if (pos == std::string::npos) {
      out.push_back(trim(std::string_view(s).substr(start)));
      break;
    }
    out.push_back(trim(std::string_view(s).substr(start, pos - start)));
    start = pos + 1;
  }
  return out;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// `# key: value` -> (key, value); false for an ordinary comment
bool parse_directive(const std::string& comment, std::string& key, std::string& value) {
  std::string body = trim(std::string_view(comment).substr(1));
  std::size_t colon = body.find(':');
  if (colon == std::string::npos || colon == 0) return false;
  key = lower(trim(std::string_view(body).substr(0, colon)));
  if (key.find(' ') != std::string::npos) return false;
  value = lower(trim(std::string_view(body).substr(colon + 1)));
  return true;
}

}  // namespace

bool strip_utf8_bom(std::string& first_line) {
  if (first_line.rfind("\xEF\xBB\xBF", 0) != 0) return false;
  first_line.erase(0, 3);
  return true;
}

std::string display_path(const std::filesystem::path& file) { return file.string(); }

int TextTable::column(const std::string& name) const {
  auto it = std::find(header.begin(), header.end(), name);
  return it == header.end() ? -1 : static_cast<int>(it - header.begin());
}

double TextTable::number(std::size_t row, std::size_t col) const {
  const std::string& text = cells[row][col];
  double v = 0.0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (!text.empty() && *first == '+') ++first;
  auto [ptr, ec] = std::from_chars(first, last, v);
  if (text.empty() || ec != std::errc() || ptr != last || !std::isfinite(v)) {
    throw InputError(display_path(file) + ": line " + std::to_string(line[row]) + ", column '" +
                     header[col] + "': '" + text + "' is not a finite number.");
  }
  return v;
}

TextTable read_text_table(const std::filesystem::path& file, TextFormat format) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(display_path(file) + ": file not found (or not a regular file).");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(display_path(file) + ": file cannot be opened for reading.");

  TextTable t;
  t.file = file;
  const char delimiter = format == TextFormat::sto ? '\t' : ',';
  bool in_sto_header = format == TextFormat::sto;
  std::string raw;
  int line_no = 0;
  while (std::getline(in, raw)) {
    ++line_no;
    if (line_no == 1) strip_utf8_bom(raw);
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    std::string s = trim(raw);
    // the .sto header block ends with `endheader`
    if (in_sto_header) {
      if (lower(s) == "endheader") in_sto_header = false;
      continue;
    }
    if (s.empty()) continue;
    if (s[0] == '#') {
      std::string key;
      std::string value;
      if (parse_directive(s, key, value)) t.directives[key] = value;
      continue;
    }
    std::vector<std::string> cells = split(s, delimiter);
    // the first data line is the header
    if (t.header.empty()) {
      t.header = std::move(cells);
      continue;
    }
    // a trailing delimiter on data rows (spreadsheet exports) is an empty last cell, not data
    if (cells.size() == t.header.size() + 1 && cells.back().empty()) cells.pop_back();
    if (cells.size() != t.header.size()) {
      throw InputError(display_path(file) + ": line " + std::to_string(line_no) + " has " +
                       std::to_string(cells.size()) + " cells but the header has " +
                       std::to_string(t.header.size()) + " columns.");
    }
    t.cells.push_back(std::move(cells));
    t.line.push_back(line_no);
  }
  if (in.bad()) throw InputError(display_path(file) + ": read error.");
  if (in_sto_header) {
    throw InputError(display_path(file) +
                     ": no 'endheader' line found; an OpenSim .sto file is expected.");
  }
  if (t.header.empty()) throw InputError(display_path(file) + ": no header line found.");
  return t;
}

}  // namespace kneesim::loads
