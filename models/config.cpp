// Config loading: keys are registered once with their type and range (config_registry.h, the
// key table in config_keys.cpp, materials in material_library.cpp); the file (read through the
// toml++ adapter, engine/io/toml_file.h) and the --set overrides are flattened to dotted keys
// and assigned through the registry, so every error names file, line, key, value and the allowed
// range.
#include "models/config.h"
#include "models/contact_law_file.h"
#include "models/contact_law_library.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/errors.h"
#include "engine/io/source_tree.h"
#include "engine/io/toml_file.h"
#include "models/config_registry.h"

namespace kneesim::models {

using namespace config_detail;

namespace {

// [conditions.<name>] set = ["key=value", ...]; the entries are removed from `flat`
std::map<std::string, std::vector<std::string>> take_conditions(std::map<std::string, Entry>& flat) {
  std::map<std::string, std::vector<std::string>> out;
  const std::string prefix = "conditions.";
  for (auto it = flat.lower_bound(prefix); it != flat.end() && it->first.starts_with(prefix);) {
    const std::string rest = it->first.substr(prefix.size());
    const auto dot = rest.find('.');
    const std::vector<std::string>* set = io::as_string_list(it->second.value);
    if (dot == std::string::npos || rest.substr(dot + 1) != "set" || !set) {
      throw InputError(it->second.origin + ": [conditions.<name>] must hold exactly one key, "
                       "set = [\"key=value\", ...] (found '" + it->first + "')");
    }
    for (const auto& text : *set) {
      if (text.find('=') == std::string::npos) {
        throw InputError(it->second.origin + ": " + it->first + " entry \"" + text +
                         "\" is not of the form \"key=value\"");
      }
    }
    out[rest.substr(0, dot)] = *set;
    it = flat.erase(it);
  }
  return out;
}

// a wear parameter given for a law that does not use it is refused: it would silently do nothing
void check_wear_keys(const Config& c, const std::map<std::string, Entry>& flat) {
  const std::vector<std::string> own = wear_law_parameter_keys(c.wear.law);
  for (auto it = flat.lower_bound("wear."); it != flat.end() && it->first.starts_with("wear.");
       ++it) {
    const std::string name = it->first.substr(5);
    if (name == "law" || name == "creep") continue;
    if (name == "creep_ratio" || name == "creep_time_s") {
      if (!c.wear.creep) {
        throw InputError(it->second.origin + ": key '" + it->first + "' is a creep parameter "
                         "but wear.creep = false (set wear.creep = true to add creep)");
      }
      continue;
    }
    if (std::find(own.begin(), own.end(), name) == own.end()) {
      std::string list;
      for (const auto& k : own) list += (list.empty() ? "" : ", ") + ("wear." + k);
      throw InputError(it->second.origin + ": key '" + it->first + "' is not a parameter of "
                       "wear.law = \"" + c.wear.law + "\" (its parameters: " +
                       (list.empty() ? std::string("none") : list) + ")" +
                       (c.wear.law == "material_pressure"
                            ? "; its exponent and p_ref are the material's "
                              "wear_pressure_exponent and wear_reference_pressure_MPa"
                            : ""));
    }
  }
}

}  // namespace

std::vector<std::string> wear_law_parameter_keys(const std::string& law) {
  if (law == "pressure_dependent_wear") return {"pressure_exponent", "reference_pressure_MPa"};
  if (law == "cross_shear")
    return {"cross_shear_gain", "pressure_exponent", "reference_pressure_MPa"};
  if (law == "contact_area") return {"cross_shear_gain"};
  if (law == "running_in") return {"running_in_excess", "running_in_cycles"};
  if (law == "incubation") return {"incubation_cycles"};
  return {};
}


Override parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 >= text.size()) {
    throw InputError("--set '" + text + "' is not of the form key=value");
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

std::filesystem::path resolve_path(const Config& config, const std::string& path) {
  std::string p = path;
  auto expand = [&p](const std::string& var, const std::string& fallback) {
    const std::string token = "${" + var + "}";
    for (auto pos = p.find(token); pos != std::string::npos; pos = p.find(token)) {
      const char* env = std::getenv(var.c_str());
      p.replace(pos, token.size(), env ? env : fallback);
    }
  };
  expand("KNEESIM_DATA", (io::source_dir() / "../shared/data").string());
  expand("KNEESIM_SOURCE", io::source_dir().string());
  std::filesystem::path out(p);
  if (out.is_relative() && !config.file.empty()) out = config.file.parent_path() / out;
  return out;
}

std::optional<NumberKey> find_number_key(const Config& config, const std::string& key) {
  Config copy = config;
  const Registry registry = make_registry(copy);
  const Field* f = registry.find(key);
  if (!f || !f->number) return std::nullopt;
  return NumberKey{*f->number, f->lo, f->hi};
}

std::vector<KeyReference> config_reference() {
  const std::vector<std::string> presets = {"stanmore", "materials_study", "iso", "displacement"};
  std::vector<Config> configs(presets.size());
  std::vector<Registry> registries;
  for (size_t p = 0; p < presets.size(); ++p) {
    configs[p].rig_preset = presets[p];
    apply_rig_preset(configs[p]);
    configs[p].material = find_material(configs[p], configs[p].material.name);
    registries.push_back(make_registry(configs[p]));
  }
  std::vector<KeyReference> out;
  for (const auto& [key, field] : registries[0].fields()) {
    KeyReference r{key, field.type, field.allowed, field.meaning, field.show(), {}};
    for (size_t p = 1; p < presets.size(); ++p) {
      const std::string v = registries[p].find(key)->show();
      if (v != r.default_value) r.preset_defaults.emplace_back(presets[p], v);
    }
    out.push_back(std::move(r));
  }
  return out;
}

Config load_config(const std::filesystem::path& file, const std::vector<Override>& overrides) {
  Config c;
  c.file = file;
  std::map<std::string, Entry> flat;
  if (!file.empty()) {
    if (!std::filesystem::exists(file)) {
      throw InputError(file.string() + ": config file not found");
    }
    flat = with_origins(io::read_toml_file(file), file.string());
    // user materials and named conditions are tables of their own, taken before the flat keys
    c.user_materials = take_material_tables(flat, "materials");
    c.conditions = take_conditions(flat);
  }
  for (const Override& o : overrides) {
    flat[o.key] = {io::parse_toml_value(o.value), "--set " + o.key + "=" + o.value};
  }
  Registry registry = make_registry(c);
  // pass 1: the preset and the material name set the defaults the other keys refine
  if (auto it = flat.find("rig.preset"); it != flat.end()) {
    registry.find("rig.preset")->assign(it->second.value, it->second.origin);
  }
  apply_rig_preset(c);
  if (auto it = flat.find("material.name"); it != flat.end()) {
    registry.find("material.name")->assign(it->second.value, it->second.origin);
  }
  c.material = find_material(c, c.material.name);
  // a factor set for this run without its own source: the override is its source, and it is
  // not known to be independent of the comparisons
  if (auto it = flat.find("material.wear_factor_mm3_per_Nmm");
      it != flat.end() && !flat.count("material.wear_factor_source")) {
    c.material.wear_factor_source = it->second.origin + " (replacing " +
                                    c.material.wear_factor_source + ")";
    c.material.wear_factor_independent = false;
  }
  // pass 2: every key, in order
  for (const auto& [key, entry] : flat) {
    const Field* f = registry.find(key);
    if (!f) {
      const std::string section = registry.keys_in_section(key);
      throw InputError(entry.origin + ": unknown config key '" + key + "'" +
                       (section.empty() ? "" : " (keys in its section: " + section + ")"));
    }
    f->assign(entry.value, entry.origin);
  }
  check_wear_keys(c, flat);
  if (c.gait_file.empty()) {
    c.gait_file = c.rig_preset == "displacement"
                      ? "${KNEESIM_SOURCE}/loads/iso14243/iso14243_3_approx.csv"
                      : "${KNEESIM_SOURCE}/loads/iso14243/iso14243_1_approx.csv";
  }
  if (c.implant_kind == "mesh" && (c.femur_mesh.empty() || c.insert_mesh.empty())) {
    throw InputError((file.empty() ? std::string("config") : file.string()) +
                     ": implant.kind = \"mesh\" needs both implant.mesh.femur and "
                     "implant.mesh.insert");
  }
  // the rigid contact law: a law file, a modulus, the calibrated law of the implant and
  // material, or the law as specified
  resolve_contact_law(c);
  return c;
}

}  // namespace kneesim::models
