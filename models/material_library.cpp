// The material library (models/materials.toml) and user material tables ([materials.<name>]
// in a config): each material's keys are assigned through the same registry as the config's
// `material.*` keys, and a wear factor must name its source.
#include <cstdio>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "engine/io/source_tree.h"
#include "models/config_registry.h"

namespace kneesim::models {
namespace config_detail {
namespace {

std::string materials_library_path() {
  return (io::source_dir() / "models/materials.toml").string();
}

}  // namespace

// materials are tables of their own: "<section>.<name>.<key>" entries, removed from `flat`
std::map<std::string, MaterialConfig> take_material_tables(std::map<std::string, Entry>& flat,
                                                           const std::string& section) {
  std::map<std::string, MaterialConfig> out;
  std::map<std::string, std::string> factor_origin;  // material -> where its factor was set
  std::set<std::string> sourced;                     // materials that name the factor's source
  std::map<std::string, std::set<std::string>> flat_keys;  // material -> the keys it sets
  const std::string prefix = section.empty() ? "" : section + ".";
  for (auto it = flat.lower_bound(prefix); it != flat.end() && it->first.starts_with(prefix);) {
    const std::string rest = it->first.substr(prefix.size());
    const auto dot = rest.find('.');
    if (dot == std::string::npos) {
      throw InputError(it->second.origin + ": '" + it->first + "' must be a table of material "
                       "properties");
    }
    const std::string name = rest.substr(0, dot);
    const std::string key = rest.substr(dot + 1);
    auto [mat, fresh] = out.try_emplace(name);
    if (fresh) mat->second.name = name;
    Registry r;
    register_material(r, "", mat->second);
    const Field* f = r.find(key);
    if (!f) {
      throw InputError(it->second.origin + ": unknown key '" + it->first + "' (allowed: "
                       "elastic_modulus_MPa, poisson, yield_MPa, density_g_per_cm3, friction, "
                       "wear_factor_mm3_per_Nmm, area_wear_coefficient, wear_factor_source, "
                       "wear_factor_independent, wear_pressure_exponent, "
                       "wear_reference_pressure_MPa, wear_pressure_source, source)");
    }
    f->assign(it->second.value, it->second.origin + " [" + it->first + "]");
    flat_keys[name].insert(key);
    if (key == "wear_factor_mm3_per_Nmm") factor_origin[name] = it->second.origin;
    if (key == "wear_factor_source") sourced.insert(name);
    it = flat.erase(it);
  }
  // a user material that leaves a property the commands need unset takes the built-in
  // default; its wear factor then counts as not independent, with that as its source
  if (section == "materials") {
    for (auto& [name, m] : out) {
      const MaterialConfig d;
      std::string taken;
      auto add = [&](const char* key, double value) {
        if (flat_keys[name].count(key)) return;
        taken += (taken.empty() ? "" : ", ") + std::string(key) + " = " + toml_number(value);
      };
      add("elastic_modulus_MPa", d.elastic_modulus_MPa);
      add("poisson", d.poisson);
      add("friction", d.friction);
      add("density_g_per_cm3", d.density_g_per_cm3);
      add("wear_factor_mm3_per_Nmm", d.wear_factor_mm3_per_Nmm);
      if (!flat_keys[name].count("wear_factor_mm3_per_Nmm")) {
        m.wear_factor_source = "not set in [materials." + name + "]: the built-in UHMWPE "
                               "default (" + d.wear_factor_source + ")";
        m.wear_factor_independent = false;
      }
      m.defaults_taken = taken;
    }
  }
  // a wear factor without its source cannot be told from a prediction's input
  for (const auto& [name, origin] : factor_origin) {
    if (!sourced.count(name) || out[name].wear_factor_source.empty()) {
      throw InputError(origin + ": material '" + name + "' sets wear_factor_mm3_per_Nmm = " +
                       toml_number(out[name].wear_factor_mm3_per_Nmm) + " without a "
                       "wear_factor_source (allowed: a non-empty text naming where the factor "
                       "comes from; add wear_factor_independent = false when it was calibrated "
                       "on what kneesim is compared with)");
    }
  }
  return out;
}

namespace {

const std::map<std::string, MaterialConfig>& library() {
  static const std::map<std::string, MaterialConfig> lib = [] {
    const std::string path = materials_library_path();
    auto flat = with_origins(io::read_toml_file(path), path);
    return take_material_tables(flat, "");
  }();
  return lib;
}

}  // namespace
}  // namespace config_detail

using config_detail::library;

std::vector<std::string> library_material_names() {
  std::vector<std::string> names;
  for (const auto& [k, v] : library()) names.push_back(k);
  return names;
}

MaterialConfig find_material(const Config& config, const std::string& name) {
  if (auto it = config.user_materials.find(name); it != config.user_materials.end()) {
    if (!it->second.defaults_taken.empty()) {
      // said once per material and process (a study builds many models of one config)
      static std::mutex mutex;
      static std::set<std::string> said;
      std::lock_guard<std::mutex> lock(mutex);
      if (said.insert(config.file.string() + "|" + name).second) {
        std::fprintf(stderr, "note: %s: material '%s' does not set every property; it takes "
                     "the built-in defaults (UHMWPE against CoCr) %s%s.\n",
                     config.file.empty() ? "config" : config.file.string().c_str(), name.c_str(),
                     it->second.defaults_taken.c_str(),
                     it->second.wear_factor_independent
                         ? ""
                         : " (its wear factor is then not independent of what kneesim is "
                           "compared with)");
      }
    }
    return it->second;
  }
  if (auto it = library().find(name); it != library().end()) return it->second;
  std::string known;
  for (const auto& n : library_material_names()) known += " " + n;
  for (const auto& [n, m] : config.user_materials) known += " " + n;
  throw InputError((config.file.empty() ? std::string("material") : config.file.string()) +
                   ": unknown material '" + name + "' (known:" + known + ")");
}

}  // namespace kneesim::models
