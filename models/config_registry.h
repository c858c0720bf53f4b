// The typed key registry behind the config (config.cpp): every key is registered once with
// its type, allowed range, one-line meaning and a way to show its current value, so that
// loading, `--set`, `kneesim config --reference` and the template all speak of the same keys.
// Internal to models/ (config.cpp, config_keys.cpp, material_library.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "engine/errors.h"
#include "engine/io/toml_file.h"
#include "models/config.h"

namespace kneesim::models::config_detail {

using Value = io::TomlValue;
using io::describe;

struct Entry {
  Value value;
  std::string origin;  // "file:line" or "--set key=value"
};

inline std::map<std::string, Entry> with_origins(const io::TomlDocument& doc, const std::string& file) {
  std::map<std::string, Entry> out;
  for (const auto& [key, e] : doc) {
    out[key] = {e.value, e.line > 0 ? file + ":" + std::to_string(e.line) : file};
  }
  return out;
}

// one registered key: how to assign it and what is allowed
struct Field {
  std::function<void(const Value&, const std::string& where)> assign;
  std::string allowed;
  const double* number = nullptr;  // the target of a number key
  double lo = 0.0, hi = 0.0;       // its allowed range
  std::string type;                // "number", "integer", "text", ... (config reference)
  std::string meaning;             // one line, for `kneesim config --reference`
  std::function<std::string()> show;  // the target's current value in TOML syntax
};

inline std::string toml_number(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

inline std::string toml_text(const std::string& v) { return "\"" + v + "\""; }

[[noreturn]] inline void fail_value(const std::string& where, const std::string& key, const Value& v,
                             const std::string& allowed) {
  throw InputError(where + ": key '" + key + "' = " + describe(v) + " is not allowed (" +
                   allowed + ")");
}

class Registry {
 public:
  void number(const std::string& key, double& target, double lo, double hi,
              const std::string& meaning) {
    std::ostringstream a;
    a << "a number in [" << lo << ", " << hi << "]";
    const std::string allowed = a.str();
    fields_[key] = {[&target, key, lo, hi, allowed](const Value& v, const std::string& where) {
                      const double* d = std::get_if<double>(&v);
                      if (!d || !std::isfinite(*d) || *d < lo || *d > hi)
                        fail_value(where, key, v, allowed);
                      target = *d;
                    },
                    allowed, &target, lo, hi, "number", meaning,
                    [&target] { return toml_number(target); }};
  }
  void integer(const std::string& key, int& target, int lo, int hi, const std::string& meaning) {
    const std::string allowed =
        "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    fields_[key] = {[&target, key, lo, hi, allowed](const Value& v, const std::string& where) {
                      const double* d = std::get_if<double>(&v);
                      if (!d || *d != std::floor(*d) || *d < lo || *d > hi)
                        fail_value(where, key, v, allowed);
                      target = static_cast<int>(*d);
                    },
                    allowed, nullptr, 0.0, 0.0, "integer", meaning,
                    [&target] { return std::to_string(target); }};
  }
  // a sign flip: exactly -1 or +1 (a fraction would silently scale the channel)
  void sign(const std::string& key, double& target, const std::string& meaning) {
    fields_[key] = {[&target, key](const Value& v, const std::string& where) {
                      const double* d = std::get_if<double>(&v);
                      if (!d || (*d != 1.0 && *d != -1.0)) fail_value(where, key, v, "-1 or 1");
                      target = *d;
                    },
                    "-1 or 1", nullptr, 0.0, 0.0, "sign", meaning,
                    [&target] { return toml_number(target); }};
  }
  void text(const std::string& key, std::string& target, const std::string& meaning) {
    fields_[key] = {[&target, key](const Value& v, const std::string& where) {
                      const std::string* s = std::get_if<std::string>(&v);
                      if (!s) fail_value(where, key, v, "a string");
                      target = *s;
                    },
                    "a string", nullptr, 0.0, 0.0, "text", meaning,
                    [&target] { return toml_text(target); }};
  }
  void choice(const std::string& key, std::string& target, std::vector<std::string> options,
              const std::string& meaning) {
    std::string allowed = "one of";
    for (const auto& o : options) allowed += " \"" + o + "\"";
    fields_[key] = {[&target, key, options, allowed](const Value& v, const std::string& where) {
                      const std::string* s = std::get_if<std::string>(&v);
                      if (!s || std::find(options.begin(), options.end(), *s) == options.end())
                        fail_value(where, key, v, allowed);
                      target = *s;
                    },
                    allowed, nullptr, 0.0, 0.0, "choice", meaning,
                    [&target] { return toml_text(target); }};
  }
  void flag(const std::string& key, bool& target, const std::string& meaning) {
    fields_[key] = {[&target, key](const Value& v, const std::string& where) {
                      const bool* b = std::get_if<bool>(&v);
                      if (!b) fail_value(where, key, v, "true or false");
                      target = *b;
                    },
                    "true or false", nullptr, 0.0, 0.0, "boolean", meaning,
                    [&target] { return std::string(target ? "true" : "false"); }};
  }
  void vec3(const std::string& key, std::array<double, 3>& target, const std::string& meaning) {
    fields_[key] = {[&target, key](const Value& v, const std::string& where) {
                      const auto* l = std::get_if<std::vector<double>>(&v);
                      if (!l || l->size() != 3) fail_value(where, key, v, "a list of 3 numbers");
                      for (int i = 0; i < 3; ++i) target[i] = (*l)[i];
                    },
                    "a list of 3 numbers", nullptr, 0.0, 0.0, "list of 3 numbers", meaning,
                    [&target] {
                      return "[" + toml_number(target[0]) + ", " + toml_number(target[1]) + ", " +
                             toml_number(target[2]) + "]";
                    }};
  }
  void list(const std::string& key, std::vector<double>& target, double lo, double hi,
            const std::string& meaning) {
    std::ostringstream a;
    a << "a list of numbers in [" << lo << ", " << hi << "]";
    const std::string allowed = a.str();
    fields_[key] = {[&target, key, lo, hi, allowed](const Value& v, const std::string& where) {
                      const auto* l = std::get_if<std::vector<double>>(&v);
                      if (!l) fail_value(where, key, v, allowed);
                      for (double x : *l)
                        if (!std::isfinite(x) || x < lo || x > hi) fail_value(where, key, v, allowed);
                      target = *l;
                    },
                    allowed, nullptr, 0.0, 0.0, "list of numbers", meaning,
                    [&target] {
                      std::string s = "[";
                      for (size_t i = 0; i < target.size(); ++i)
                        s += (i ? ", " : "") + toml_number(target[i]);
                      return s + "]";
                    }};
  }
  void strings(const std::string& key, std::vector<std::string>& target,
               const std::string& meaning) {
    fields_[key] = {[&target, key](const Value& v, const std::string& where) {
                      const auto* l = io::as_string_list(v);
                      if (!l) fail_value(where, key, v, "a list of strings");
                      target = *l;
                    },
                    "a list of strings", nullptr, 0.0, 0.0, "list of strings", meaning,
                    [&target] {
                      std::string s = "[";
                      for (size_t i = 0; i < target.size(); ++i)
                        s += (i ? ", " : "") + toml_text(target[i]);
                      return s + "]";
                    }};
  }
  const std::map<std::string, Field>& fields() const { return fields_; }
  const Field* find(const std::string& key) const {
    auto it = fields_.find(key);
    return it == fields_.end() ? nullptr : &it->second;
  }
  std::string keys_in_section(const std::string& key) const {
    const std::string section = key.substr(0, key.rfind('.') + 1);
    std::string out;
    for (const auto& [k, f] : fields_) {
      if (k.rfind(section, 0) == 0 && k.find('.', section.size()) == std::string::npos)
        out += (out.empty() ? "" : ", ") + k;
    }
    return out;
  }

 private:
  std::map<std::string, Field> fields_;
};

// the key table (config_keys.cpp): every key of Config with its range and meaning
Registry make_registry(Config& c);
// a material's keys under `prefix` ("material." or "" inside a material table)
void register_material(Registry& r, const std::string& prefix, MaterialConfig& m);
// the defaults of c.rig_preset (config_keys.cpp)
void apply_rig_preset(Config& c);
// materials are tables of their own: "<section>.<name>.<key>" entries, removed from `flat`
// (material_library.cpp)
std::map<std::string, MaterialConfig> take_material_tables(std::map<std::string, Entry>& flat,
                                                           const std::string& section);

}  // namespace kneesim::models::config_detail
