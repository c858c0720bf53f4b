#include "loads/iso14243/text_table.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
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

// the first of ';', tab, '|' that `line` contains, as it is named in messages; "" for none
std::string other_separator(const std::string& line) {
  if (line.find(';') != std::string::npos) return "';'";
  if (line.find('\t') != std::string::npos) return "tabs";
  if (line.find('|') != std::string::npos) return "'|'";
  return "";
}

// the first token of `line` of the form digits,digits (a number with a decimal comma in a
// line separated by something else), or ""
std::string first_decimal_comma(const std::string& line) {
  for (std::size_t i = 1; i + 1 < line.size(); ++i) {
    if (line[i] != ',' || !std::isdigit(static_cast<unsigned char>(line[i - 1])) ||
        !std::isdigit(static_cast<unsigned char>(line[i + 1]))) {
      continue;
    }
    std::size_t b = i;
    while (b > 0 && (std::isdigit(static_cast<unsigned char>(line[b - 1])) || line[b - 1] == '-')) --b;
    std::size_t e = i + 1;
    while (e < line.size() && std::isdigit(static_cast<unsigned char>(line[e]))) ++e;
    return line.substr(b, e - b);
  }
  return "";
}

}  // namespace

std::string separator_hint(const std::string& header_line, const std::string& row_line,
                           std::size_t header_cells, std::size_t row_cells) {
  const std::string reads =
      "; kneesim reads comma-separated values with a decimal point, e.g. 0.5, not 0,5)";
  std::string sep = other_separator(header_line);
  if (sep.empty()) sep = other_separator(row_line);
  const std::string comma_number = first_decimal_comma(row_line);
  if (!sep.empty()) {
    return " (the file looks separated by " + sep +
           (comma_number.empty() ? std::string()
                                 : " with decimal commas ('" + comma_number + "')") +
           reads;
  }
  if (row_cells > header_cells && !comma_number.empty()) {
    // which comma is the decimal one cannot be told from the text: none is named
    return " (likely a decimal comma: " + std::to_string(row_cells - header_cells) +
           " more comma(s) than the header's; a number written 0,5 is read as two values" + reads;
  }
  return "";
}

std::string decimal_comma_hint(const std::string& text) {
  std::string dotted = text;
  const std::size_t comma = dotted.find(',');
  if (comma == std::string::npos || dotted.find(',', comma + 1) != std::string::npos) return "";
  dotted[comma] = '.';
  char* end = nullptr;
  const double v = std::strtod(dotted.c_str(), &end);
  if (end == dotted.c_str() || *end != '\0' || !std::isfinite(v)) return "";
  return " (a decimal comma? write " + dotted + "; kneesim reads numbers with a decimal point)";
}

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
                     header[col] + "': '" + text + "' is not a finite number" +
                     decimal_comma_hint(text) + ".");
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
  std::string header_line;
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
      // a spreadsheet in a decimal-comma locale writes ';' (or tabs) between cells: the
      // header is then one cell, which no column name matches
      if (format == TextFormat::csv && cells.size() == 1 && !other_separator(s).empty()) {
        throw InputError(display_path(file) + ": line " + std::to_string(line_no) +
                         " (header) '" + s + "' is separated by " + other_separator(s) +
                         ", not ','; kneesim reads comma-separated values with a decimal point, "
                         "e.g. 0.5, not 0,5.");
      }
      header_line = s;
      t.header = std::move(cells);
      continue;
    }
    // a trailing delimiter on data rows (spreadsheet exports) is an empty last cell, not data
    if (cells.size() == t.header.size() + 1 && cells.back().empty()) cells.pop_back();
    if (cells.size() != t.header.size()) {
      throw InputError(display_path(file) + ": line " + std::to_string(line_no) + " has " +
                       std::to_string(cells.size()) + " cells but the header has " +
                       std::to_string(t.header.size()) + " columns" +
                       (format == TextFormat::csv
                            ? separator_hint(header_line, s, t.header.size(), cells.size())
                            : std::string()) +
                       ".");
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
