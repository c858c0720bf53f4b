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

std::string where(const std::filesystem::path& file, const io::TomlEntry& e) {
  return file.string() + (e.line > 0 ? ":" + std::to_string(e.line) : "");
}

const io::TomlEntry& require(const io::TomlDocument& doc, const std::filesystem::path& file,
                             const std::string& key) {
  const auto it = doc.find(kSection + key);
  if (it == doc.end()) {
    throw InputError(file.string() + ": calibrated contact law file lacks the key '" +
                     kSection + key + "' (written by kneesim calibrate-contact).");
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

CalibratedContactLaw read_contact_law_file(const std::filesystem::path& file,
                                           const std::string& material,
                                           const std::string& implant) {
  if (!std::filesystem::is_regular_file(file)) {
    throw InputError(file.string() + ": calibrated contact law file (contact.law_file) not found.");
  }
  const io::TomlDocument doc = io::read_toml_file(file);
  for (const auto& [key, entry] : doc) {
    if (key.rfind(kSection, 0) != 0) {
      throw InputError(where(file, entry) + ": unknown key '" + key +
                       "' in a calibrated contact law file (allowed: the [calibrated_contact] "
                       "table).");
    }
  }
  CalibratedContactLaw law;
  law.material = text(doc, file, "material");
  law.implant = text(doc, file, "implant");
  law.law = text(doc, file, "law");
  law.foundation_modulus_MPa = number(doc, file, "foundation_modulus_MPa", 0.0, 1e6);
  law.specified_modulus_MPa = number(doc, file, "specified_modulus_MPa", 0.0, 1e6);
  if (doc.count(std::string(kSection) + "fitted_on")) law.fitted_on = text(doc, file, "fitted_on");
  if (law.law != "linear" && law.law != "nonlinear") {
    throw InputError(where(file, require(doc, file, "law")) + ": key '" + kSection +
                     "law' = \"" + law.law + "\" is not allowed (linear, nonlinear).");
  }
  if (law.material != material) {
    throw InputError(where(file, require(doc, file, "material")) +
                     ": the contact law was calibrated for material \"" + law.material +
                     "\", the config's material.name is \"" + material +
                     "\" (calibrate it for that material: kneesim calibrate-contact --material " +
                     material + ").");
  }
  if (law.implant != implant) {
    throw InputError(where(file, require(doc, file, "implant")) +
                     ": the contact law was calibrated for implant \"" + law.implant +
                     "\", the config's implant is \"" + implant + "\".");
  }
  return law;
}

std::string implant_identity(const Config& config) {
  return config.implant_kind == "generic" ? std::string("generic") : config.insert_mesh;
}

void write_contact_law_file(const std::filesystem::path& file, const CalibratedContactLaw& law) {
  std::ostringstream s;
  s.precision(10);
  s << "# written by kneesim calibrate-contact; named by a config as contact.law_file\n"
    << "[calibrated_contact]\n"
    << "material = \"" << law.material << "\"\n"
    << "implant = \"" << law.implant << "\"\n"
    << "law = \"" << law.law << "\"\n"
    << "foundation_modulus_MPa = " << law.foundation_modulus_MPa << "\n"
    << "specified_modulus_MPa = " << law.specified_modulus_MPa << "\n"
    << "fitted_on = \"" << law.fitted_on << "\"\n";
  io::write_file_atomic(file, s.str());
}

}  // namespace kneesim::models
