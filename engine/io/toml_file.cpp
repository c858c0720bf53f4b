#include "engine/io/toml_file.h"

#include <sstream>
#include <toml++/toml.h>

#include "engine/errors.h"

namespace kneesim::io {
namespace {

std::string where(const std::string& origin, const toml::node& node) {
  const auto line = node.source().begin.line;
  return line > 0 ? origin + ":" + std::to_string(line) : origin;
}

TomlValue convert(const toml::node& node, const std::string& key, const std::string& origin) {
  if (const auto* arr = node.as_array()) {
    if (!arr->empty() && (*arr)[0].is_string()) {
      std::vector<std::string> list;
      for (const auto& item : *arr) {
        auto s = item.value_exact<std::string>();
        if (!s) throw InputError(where(origin, item) + ": key '" + key + "' must be a list of strings only");
        list.push_back(*s);
      }
      return list;
    }
    std::vector<double> list;
    for (const auto& item : *arr) {
      auto d = item.is_number() ? item.value<double>() : std::nullopt;
      if (!d) throw InputError(where(origin, item) + ": key '" + key + "' must be a list of numbers only");
      list.push_back(*d);
    }
    return list;
  }
  if (auto b = node.value_exact<bool>()) return *b;
  if (node.is_number()) return *node.value<double>();
  if (auto s = node.value_exact<std::string>()) return *s;
  throw InputError(where(origin, node) + ": key '" + key +
                   "' has a value of an unsupported type (use a number, string, boolean or list)");
}

void flatten(const toml::table& table, const std::string& prefix, const std::string& origin,
             TomlDocument& out) {
  for (const auto& [k, node] : table) {
    const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (const auto* sub = node.as_table()) {
      flatten(*sub, key, origin, out);
    } else {
      out[key] = {convert(node, key, origin), static_cast<int>(node.source().begin.line)};
    }
  }
}

}  // namespace

TomlDocument read_toml_file(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(name + ": file not found (or not a regular file)");
  }
  toml::table root;
  try {
    root = toml::parse_file(name);
  } catch (const toml::parse_error& e) {
    throw InputError(name + ":" + std::to_string(e.source().begin.line) + ": not valid TOML (" +
                     std::string(e.description()) + ")");
  }
  TomlDocument out;
  flatten(root, "", name, out);
  return out;
}

TomlValue parse_toml_value(const std::string& text) {
  toml::table t;
  try {
    t = toml::parse("v = " + text);
  } catch (const toml::parse_error&) {
    return text;  // a bare word is a string
  }
  const toml::node* node = t.get("v");
  if (node == nullptr || node->is_table()) return text;
  return convert(*node, "v", "value '" + text + "'");
}

const std::vector<std::string>* as_string_list(const TomlValue& value) {
  static const std::vector<std::string> kEmpty;
  if (const auto* numbers = std::get_if<std::vector<double>>(&value)) {
    return numbers->empty() ? &kEmpty : nullptr;
  }
  return std::get_if<std::vector<std::string>>(&value);
}

std::string describe(const TomlValue& v) {
  std::ostringstream s;
  if (auto d = std::get_if<double>(&v)) {
    s << *d;
  } else if (auto str = std::get_if<std::string>(&v)) {
    s << '"' << *str << '"';
  } else if (auto b = std::get_if<bool>(&v)) {
    s << (*b ? "true" : "false");
  } else if (auto nums = std::get_if<std::vector<double>>(&v)) {
    s << '[';
    for (size_t i = 0; i < nums->size(); ++i) s << (i ? ", " : "") << (*nums)[i];
    s << ']';
  } else {
    const auto& strs = std::get<std::vector<std::string>>(v);
    s << '[';
    for (size_t i = 0; i < strs.size(); ++i) s << (i ? ", " : "") << '"' << strs[i] << '"';
    s << ']';
  }
  return s.str();
}

}  // namespace kneesim::io
