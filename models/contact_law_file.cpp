#include "models/contact_law_file.h"

#include <cmath>
#include <sstream>

#include "engine/errors.h"
#include "engine/io/atomic_file.h"
#include "engine/io/toml_file.h"
#include "models/config.h"

namespace kneesim::models {
namespace {

constexpr const char* kSection = "calibrated_contact.";
constexpr const char* kProvenance = "calibrated_contact.provenance.";

std::string where(const std::filesystem::path& file, const io::TomlEntry& e) {
  return file.string() + (e.line > 0 ? ":" + std::to_string(e.line) : "");
}

const io::TomlEntry& require(const io::TomlDocument& doc, const std::filesystem::path& file,
                             const std::string& key) {
  const auto it = doc.find(kSection + key);
  if (it == doc.end()) {
    throw InputError(file.string() + ": calibrated contact law file lacks the key '" +
                     kSection + key + "' (written by kneesim calibrate-contact; a file of an "
                     "earlier release lacks the hashes: calibrate again).");
  }
  return it->second;
}

std::string text(const io::TomlDocument& doc, const std::filesystem::path& file,
                 const std::string& key) {
  const io::TomlEntry& e = require(doc, file, key);
  if (const auto* s = std::get_if<std::string>(&e.value)) return *s;
  throw InputError(where(file, e) + ": key '" + kSection + key + "' = " + io::describe(e.value) +
                   " must be a string.");
}

double number(const io::TomlDocument& doc, const std::filesystem::path& file,
              const std::string& key, double lo, double hi) {
  const io::TomlEntry& e = require(doc, file, key);
  const auto* v = std::get_if<double>(&e.value);
  if (!v || !std::isfinite(*v) || *v <= lo || *v > hi) {
    std::ostringstream s;
    s << where(file, e) << ": key '" << kSection << key << "' = " << io::describe(e.value)
      << " is outside the allowed range (" << lo << ", " << hi << "] MPa.";
    throw InputError(s.str());
  }
  return *v;
}


}  // namespace

CalibratedContactLaw read_contact_law_file(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file)) {
    throw InputError(file.string() + ": calibrated contact law file (contact.law_file) not found.");
  }
  const io::TomlDocument doc = io::read_toml_file(file);
  CalibratedContactLaw law;
  for (const auto& [key, entry] : doc) {
    if (key.rfind(kProvenance, 0) == 0) {
      // provenance is carried as written (a string quoted again, a number as text)
      const std::string name = key.substr(std::string(kProvenance).size());
      if (const auto* s = std::get_if<std::string>(&entry.value)) {
        law.provenance.emplace_back(name, toml_quoted(*s));
      } else {
        law.provenance.emplace_back(name, io::describe(entry.value));
      }
      continue;
    }
    static const char* const kKeys[] = {"material", "implant", "key", "implant_hash",
                                        "material_hash", "settings_hash", "law",
                                        "foundation_modulus_MPa", "exponent",
                                        "specified_modulus_MPa", "fitted_on"};
    bool known = false;
    for (const char* k : kKeys) known = known || key == std::string(kSection) + k;
    if (!known) {
      throw InputError(where(file, entry) + ": unknown key '" + key +
                       "' in a calibrated contact law file (allowed: material, implant, key, "
                       "implant_hash, material_hash, settings_hash, law, foundation_modulus_MPa, "
                       "exponent, specified_modulus_MPa, fitted_on and the provenance table).");
    }
  }
  law.material = text(doc, file, "material");
  law.implant = text(doc, file, "implant");
  law.key.key = text(doc, file, "key");
  law.key.implant = text(doc, file, "implant_hash");
  law.key.material = text(doc, file, "material_hash");
  law.key.settings = text(doc, file, "settings_hash");
  law.law = text(doc, file, "law");
  law.foundation_modulus_MPa = number(doc, file, "foundation_modulus_MPa", 0.0, 1e6);
  // a law without an exponent is one of physics.md's laws (n = 1)
  if (doc.count(std::string(kSection) + "exponent")) {
    law.exponent = number(doc, file, "exponent", 0.2, 2.0);
  }
  law.specified_modulus_MPa = number(doc, file, "specified_modulus_MPa", 0.0, 1e6);
  if (doc.count(std::string(kSection) + "fitted_on")) law.fitted_on = text(doc, file, "fitted_on");
  if (law.law != "linear" && law.law != "nonlinear") {
    throw InputError(where(file, require(doc, file, "law")) + ": key '" + kSection +
                     "law' = \"" + law.law + "\" is not allowed (linear, nonlinear).");
  }
  return law;
}

void check_contact_law_fits(const std::filesystem::path& file, const CalibratedContactLaw& law,
                            const std::string& material, const std::string& implant,
                            const ContactLawKey& key) {
  if (law.material != material) {
    throw InputError(file.string() + ": the contact law was calibrated for material \"" +
                     law.material + "\", the config's material.name is \"" + material +
                     "\" (calibrate it for that material: kneesim calibrate-contact --set "
                     "material.name=" + material + ").");
  }
  if (law.key.material != key.material) {
    throw InputError(file.string() + ": the contact law was calibrated for material \"" +
                     law.material + "\" with other constants (material hash " +
                     law.key.material + ", the config's " + key.material +
                     "): calibrate it for the config's material.");
  }
  if (law.key.implant != key.implant) {
    throw InputError(file.string() + ": the contact law was calibrated for implant \"" +
                     law.implant + "\" (geometry hash " + law.key.implant +
                     "), the config's implant \"" + implant + "\" hashes to " + key.implant +
                     (law.implant == implant ? " (its meshes or placement changed since)" : "") +
                     ": calibrate it for this implant.");
  }
}

std::string implant_identity(const Config& config) {
  return config.implant_kind == "generic" ? std::string("generic") : config.insert_mesh;
}

void write_contact_law_file(const std::filesystem::path& file, const CalibratedContactLaw& law) {
  std::ostringstream s;
  // 17 significant digits: the law read back is the same double as the one fitted, so the run
  // that calibrates on first use and every later run that finds the cached file agree bit for bit
  s.precision(17);
  s << "# written by kneesim calibrate-contact; found by its key (models/contact_law_library.h)\n"
    << "# or named by a config as contact.law_file\n"
    << "[calibrated_contact]\n"
    << "material = " << toml_quoted(law.material) << "\n"
    << "implant = " << toml_quoted(law.implant) << "\n"
    << "key = " << toml_quoted(law.key.key) << "\n"
    << "implant_hash = " << toml_quoted(law.key.implant) << "\n"
    << "material_hash = " << toml_quoted(law.key.material) << "\n"
    << "settings_hash = " << toml_quoted(law.key.settings) << "\n"
    << "law = " << toml_quoted(law.law) << "\n"
    << "foundation_modulus_MPa = " << law.foundation_modulus_MPa << "\n"
    << "exponent = " << law.exponent << "\n"
    << "specified_modulus_MPa = " << law.specified_modulus_MPa << "\n"
    << "fitted_on = " << toml_quoted(law.fitted_on) << "\n";
  if (!law.provenance.empty()) {
    s << "\n[calibrated_contact.provenance]\n";
    for (const auto& [k, v] : law.provenance) s << k << " = " << v << "\n";
  }
  io::write_file_atomic(file, s.str());
}

std::string toml_quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace kneesim::models
