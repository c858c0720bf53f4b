// The toml++ adapter (design.md: each third-party library behind one adapter file). A TOML
// document is read into dotted keys ("rig.restraint.gap_mm") with plain values and the line
// they came from, so the config readers (models/config.cpp, wear/particles/particles_config.cpp)
// validate keys and ranges without seeing toml++ types.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace kneesim::io {

using TomlValue =
    std::variant<double, std::string, bool, std::vector<double>, std::vector<std::string>>;

struct TomlEntry {
  TomlValue value;
  int line = 0;  // 1-based line in the file; 0 when parsed from a string
};

// dotted key -> value; integers are read as doubles; arrays must hold only numbers or only
// strings. Throws InputError naming the file and line for unreadable files, syntax errors and
// unsupported values (dates, mixed or nested arrays, arrays of tables).
using TomlDocument = std::map<std::string, TomlEntry>;

TomlDocument read_toml_file(const std::filesystem::path& file);

// One value written as in TOML ("2.5", "true", "\"uhmwpe\"", "[1, 2]"); anything that does not
// parse as a TOML value is taken as a bare string (so --set material.name=peek works).
TomlValue parse_toml_value(const std::string& text);

// the value as a list of strings, or nullptr when it is not one. An empty TOML array has no
// element type (it is stored as an empty number list) and counts as an empty string list.
const std::vector<std::string>* as_string_list(const TomlValue& value);

// the value as the user would write it, for error messages
std::string describe(const TomlValue& value);

}  // namespace kneesim::io
