#include "models/contact_law_library.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>

#include "engine/contact_law.h"
#include "engine/errors.h"
#include "engine/io/source_tree.h"
#include "models/distance_field_disk.h"

namespace kneesim::models {
namespace {

struct Registry {
  std::mutex mutex;
  std::map<std::string, std::pair<std::filesystem::path, CalibratedContactLaw>> laws;  // by key
};

Registry& registry() {
  static Registry r;
  return r;
}

// a provenance number, NaN when absent or not a number
double provenance_number(const CalibratedContactLaw& law, const std::string& name) {
  for (const auto& [k, v] : law.provenance) {
    if (k != name) continue;
    char* end = nullptr;
    const double x = std::strtod(v.c_str(), &end);
    return end && *end == '\0' ? x : NAN;
  }
  return NAN;
}

void apply(Config& c, const CalibratedContactLaw& law, const std::filesystem::path& file,
           const std::string& source) {
  c.contact_law = law.law;
  c.contact_foundation_modulus_MPa = law.foundation_modulus_MPa;
  c.contact_law_exponent = law.exponent;
  c.contact_law_resolution.source = source;
  c.contact_law_resolution.file = file.string();
  c.contact_law_resolution.needs_calibration = false;
  c.contact_law_resolution.provenance = law.provenance;
  c.contact_law_resolution.provenance.insert(c.contact_law_resolution.provenance.begin(),
                                             {"fitted_on", "\"" + law.fitted_on + "\""});
}

}  // namespace

std::filesystem::path shipped_contact_law_dir() {
  return io::source_dir() / "models" / "contact_laws";
}

std::filesystem::path contact_law_cache_dir() {
  const std::filesystem::path dir = find_field_cache_dir();
  return dir.empty() ? dir : dir / "contact_laws";
}

const std::vector<std::pair<std::filesystem::path, CalibratedContactLaw>>& shipped_contact_laws() {
  static const auto laws = [] {
    std::vector<std::pair<std::filesystem::path, CalibratedContactLaw>> v;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(shipped_contact_law_dir(), ec)) {
      if (e.path().extension() == ".toml") v.emplace_back(e.path(), read_contact_law_file(e.path()));
    }
    std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    return v;
  }();
  return laws;
}

void remember_contact_law(const CalibratedContactLaw& law, const std::filesystem::path& file) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  registry().laws[law.key.key] = {file, law};
}

void resolve_contact_law(Config& c) {
  ContactLawResolution& r = c.contact_law_resolution;
  r = {};
  if (c.insert_kind == "deformable") {
    r.source = "unused";
    return;
  }
  if (c.contact_calibration == "off" && c.contact_law_file.empty() &&
      !(c.contact_foundation_modulus_MPa > 0.0)) {
    r.source = "specified";
    r.warning = specified_law_warning(c);
    return;
  }
  // a mesh implant whose files are not there yet (a template's placeholders) or are not files (a
  // folder): loading the config is not refused for it; building the model is, with the mesh
  // reader's message naming the file (source "unresolved")
  if (c.implant_kind == "mesh") {
    for (const std::string& mesh : {c.femur_mesh, c.insert_mesh}) {
      std::error_code ec;
      if (!std::filesystem::is_regular_file(resolve_path(c, mesh), ec)) {
        r.source = "unresolved";
        r.note = resolve_path(c, mesh).string() + ": not a readable mesh file";
        return;
      }
    }
  }
  // the key of the reference the config's law is calibrated under (models/contact_law_key.h)
  const ContactLawKey key = make_contact_law_key(make_calibration_config(c));
  r.key = key.key;
  const std::string implant = implant_identity(c);
  if (!c.contact_law_file.empty()) {
    const std::filesystem::path file = resolve_path(c, c.contact_law_file);
    const CalibratedContactLaw law = read_contact_law_file(file);
    check_contact_law_fits(file, law, c.material.name, implant, key);
    apply(c, law, file, "law_file");
    return;
  }
  if (c.contact_foundation_modulus_MPa > 0.0) {
    r.source = "modulus";
    return;
  }
  if (c.contact_calibration == "off") {
    r.source = "specified";
    r.warning = specified_law_warning(c);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(registry().mutex);
    const auto it = registry().laws.find(key.key);
    if (it != registry().laws.end()) {
      apply(c, it->second.second, it->second.first, "calibrated");
      return;
    }
  }
  for (const auto& [file, law] : shipped_contact_laws()) {
    if (law.key.key == key.key) {
      apply(c, law, file, "library");
      return;
    }
  }
  const std::filesystem::path dir = contact_law_cache_dir();
  if (!dir.empty()) {
    const std::filesystem::path file = dir / (key.key + ".toml");
    if (std::filesystem::exists(file)) {
      try {
        const CalibratedContactLaw law = read_contact_law_file(file);
        if (law.key.key == key.key) {
          apply(c, law, file, "cache");
          return;
        }
        r.note = file.string() + " holds the law of another key (" + law.key.key +
                 "): not used, calibrating again";
      } catch (const InputError& e) {
        r.note = std::string("a cached law could not be read (") + e.what() +
                 "): not used, calibrating again";
      }
    }
  }
  // a law of the same implant path and material with other content: the meshes changed
  for (const auto& [file, law] : shipped_contact_laws()) {
    if (law.implant == implant && law.material == c.material.name && law.key.implant != key.implant) {
      r.note = file.string() + " was calibrated for \"" + implant + "\" with geometry hash " +
               law.key.implant + ", the config's implant hashes to " + key.implant +
               " (its meshes or placement changed): not used";
    }
  }
  if (c.contact_calibration == "first_use") {
    r.needs_calibration = true;  // run::ensure_contact_law calibrates it
    return;
  }
  // the stated fallback: the law as specified, with the warning in the console and summary.json
  r.source = "specified";
  r.warning = "no calibrated contact law for implant \"" + implant + "\" and material \"" +
              c.material.name + "\" (kneesim calibrate-contact makes one; contact.calibration = "
              "\"first_use\" calibrates it on first use): " + specified_law_warning(c);
}

void transfer_contact_law(const Config& nominal, Config& trial) {
  const double k_nominal = engine::foundation_modulus(nominal.material.elastic_modulus_MPa,
                                                      nominal.material.poisson);
  const double k_trial = engine::foundation_modulus(trial.material.elastic_modulus_MPa,
                                                    trial.material.poisson);
  ContactLawResolution& r = trial.contact_law_resolution;
  r.needs_calibration = false;
  r.source = "nominal_ratio";
  r.file = nominal.contact_law_resolution.file;
  r.provenance = nominal.contact_law_resolution.provenance;
  trial.contact_law = nominal.contact_law;
  trial.contact_law_exponent = nominal.contact_law_exponent;
  if (nominal.contact_foundation_modulus_MPa > 0.0) {
    trial.contact_foundation_modulus_MPa = nominal.contact_foundation_modulus_MPa * k_trial / k_nominal;
    char buf[200];
    std::snprintf(buf, sizeof buf, "the nominal law's K_eff / K = %.4f carried over (no law of "
                  "this trial's implant and material)", nominal.contact_foundation_modulus_MPa / k_nominal);
    r.note = buf;
  } else {
    r.note = "the nominal config's law as specified";
    r.warning = nominal.contact_law_resolution.warning;
  }
}

std::string specified_law_warning(const Config& c) {
  const double k = engine::foundation_modulus(c.material.elastic_modulus_MPa, c.material.poisson);
  // the shipped laws of this material (by name), else of every material
  double peak_lo = INFINITY, peak_hi = -INFINITY, mean_lo = INFINITY, mean_hi = -INFINITY;
  int n = 0;
  for (const bool same_material : {true, false}) {
    for (const auto& [file, law] : shipped_contact_laws()) {
      if (same_material && law.material != c.material.name) continue;
      const double dp = provenance_number(law, "stance_peak_MPa_deformable");
      const double sp = provenance_number(law, "stance_peak_MPa_specified");
      const double dm = provenance_number(law, "stance_mean_MPa_deformable");
      const double sm = provenance_number(law, "stance_mean_MPa_specified");
      if (!(dp > 0 && dm > 0 && std::isfinite(sp) && std::isfinite(sm))) continue;
      peak_lo = std::min(peak_lo, 100 * (sp / dp - 1));
      peak_hi = std::max(peak_hi, 100 * (sp / dp - 1));
      mean_lo = std::min(mean_lo, 100 * (sm / dm - 1));
      mean_hi = std::max(mean_hi, 100 * (sm / dm - 1));
      ++n;
    }
    if (n > 0) {
      // "+87 %" from one law, "+5 to +87 %" from several
      auto range = [](double lo, double hi) {
        char r[64];
        if (std::lround(lo) == std::lround(hi)) {
          std::snprintf(r, sizeof r, "%+.0f %%", lo);
        } else {
          std::snprintf(r, sizeof r, "%+.0f to %+.0f %%", lo, hi);
        }
        return std::string(r);
      };
      char buf[512];
      std::snprintf(buf, sizeof buf,
                    "contact law as specified: K = (1-nu)E/((1+nu)(1-2nu)) "
                    "= %.0f MPa; against the deformable insert, pressures of this law ran %s "
                    "(stance peak) and %s (stance mean) for %s on the shipped implants",
                    k, range(peak_lo, peak_hi).c_str(), range(mean_lo, mean_hi).c_str(),
                    same_material ? c.material.name.c_str() : "the shipped materials");
      return buf;
    }
  }
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "contact law as specified: K = (1-nu)E/((1+nu)(1-2nu)) "
                "= %.0f MPa, not calibrated against the deformable insert", k);
  return buf;
}

}  // namespace kneesim::models
