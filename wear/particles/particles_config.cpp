#include "wear/particles/particles_config.h"

#include <cstdio>
#include <set>

#include "engine/errors.h"
#include "engine/io/toml_file.h"

namespace kneesim::particles {
namespace {

// reads typed values from the flattened document and remembers which keys it read, so that a
// misspelt key is an error instead of a silently ignored input
struct Reader {
  std::string file;
  const io::TomlDocument& doc;
  mutable std::set<std::string> read;

  const io::TomlEntry* find(const std::string& section, const std::string& key) const {
    const std::string full = section.empty() ? key : section + "." + key;
    read.insert(full);
    const auto it = doc.find(full);
    return it == doc.end() ? nullptr : &it->second;
  }
  std::string where(const std::string& section, const std::string& key,
                    const io::TomlEntry& e) const {
    return file + ":" + std::to_string(e.line) + ": " +
           (section.empty() ? key : "[" + section + "] " + key);
  }

  // a number at [section] key (section empty = top level) within [lo, hi], or `fallback`
  double number(const std::string& section, const std::string& key, double fallback, double lo,
                double hi) const {
    const io::TomlEntry* e = find(section, key);
    if (e == nullptr) return fallback;
    const double* v = std::get_if<double>(&e->value);
    if (!v) throw InputError(where(section, key, *e) + " = " + io::describe(e->value) + " must be a number");
    if (!(*v >= lo && *v <= hi)) {
      char buf[512];
      std::snprintf(buf, sizeof buf, "%s = %g is not allowed; the allowed range is %g to %g",
                    where(section, key, *e).c_str(), *v, lo, hi);
      throw InputError(buf);
    }
    return *v;
  }
  // target = scale * value when the key is present (range checked in the file's unit);
  // an absent key leaves target bit-identical to the preset
  void set(const std::string& section, const std::string& key, double& target, double scale,
           double lo, double hi) const {
    if (doc.count(section.empty() ? key : section + "." + key)) {
      target = scale * number(section, key, 0.0, lo, hi);
    } else {
      find(section, key);
    }
  }
  template <class Int>
  void set_int(const std::string& section, const std::string& key, Int& target, double lo,
               double hi) const {
    target = static_cast<Int>(number(section, key, static_cast<double>(target), lo, hi));
  }
  std::string text(const std::string& section, const std::string& key,
                   const std::string& fallback) const {
    const io::TomlEntry* e = find(section, key);
    if (e == nullptr) return fallback;
    const std::string* v = std::get_if<std::string>(&e->value);
    if (!v) throw InputError(where(section, key, *e) + " = " + io::describe(e->value) + " must be a string");
    return *v;
  }
  void flag(const std::string& section, const std::string& key, bool& target) const {
    const io::TomlEntry* e = find(section, key);
    if (e == nullptr) return;
    const bool* v = std::get_if<bool>(&e->value);
    if (!v) throw InputError(where(section, key, *e) + " = " + io::describe(e->value) + " must be true or false");
    target = *v;
  }
  void reject_unread() const {
    for (const auto& [key, e] : doc) {
      if (read.count(key) == 0) {
        throw InputError(file + ":" + std::to_string(e.line) + ": unknown key '" + key +
                         "' (see wear/particles/particles_config.h or docs/particles.md for the keys)");
      }
    }
  }
};

void read_body(const Reader& r, const std::string& s, BodySpec& b) {
  constexpr double kBig = 1e30;
  r.set(s, "E_GPa", b.elastic.youngs_modulus, 1e9, 1e-4, 2000);
  r.set(s, "nu", b.elastic.poisson_ratio, 1.0, 0.0, 0.499);
  r.set(s, "hardness_GPa", b.hardness, 1e9, 1e-5, 100);
  r.set(s, "yield_GPa", b.yield_stress, 1e9, 1e-5, 100);
  r.set(s, "rq_nm", b.roughness.rq, 1e-9, 1e-3, 1e5);
  r.set(s, "skewness", b.roughness.skewness, 1.0, -5, 5);
  r.set(s, "kurtosis", b.roughness.kurtosis, 1.0, 1.0, 50);
  r.set(s, "correlation_length_nm", b.roughness.correlation_length, 1e-9, 1e-3, kBig);
  r.set(s, "peklenik_gamma", b.roughness.gamma, 1.0, 1e-3, 1e3);
  r.set(s, "lambda_s_nm", b.roughness.lambda_s, 1e-9, 0.0, 1e9);
  r.set_int(s, "seed", b.roughness.seed, 0, 1e15);
  r.set(s, "film_thickness_nm", b.elastic.film_thickness, 1e-9, 0.0, 1e6);
  r.set(s, "film_E_GPa", b.elastic.film_modulus, 1e9, 0.0, 2000);
  r.set(s, "film_nu", b.elastic.film_poisson, 1.0, 0.0, 0.499);
  r.set(s, "film_yield_GPa", b.film_yield_stress, 1e9, 0.0, 100);
  r.set(s, "film_hardness_GPa", b.film_hardness, 1e9, 0.0, 100);
  if (b.elastic.film_thickness > 0.0 && !(b.elastic.film_modulus > 0.0)) {
    throw InputError(r.file + ": [" + s + "] film_E_GPa must be > 0 when film_thickness_nm > 0");
  }
  if (b.elastic.film_thickness > 0.0 && !(b.film_yield_stress > 0.0)) {
    throw InputError(r.file + ": [" + s + "] film_yield_GPa must be > 0 when film_thickness_nm > 0");
  }
  b.surface_csv = r.text(s, "surface_csv", b.surface_csv);
}

}  // namespace

ParticleModelConfig read_particle_config(const std::filesystem::path& path,
                                         const KneeContactPressureFn& knee_pressure) {
  const std::string file = path.string();
  const io::TomlDocument doc = io::read_toml_file(path);
  const Reader r{file, doc, {}};
  const PairName pair = parse_pair(r.text("", "pair", "steel-steel"), file + ": pair");
  KneeContactPressure p;
  if (doc.count("contact_pressure_MPa")) {
    if (!is_knee_pair(pair)) {
      throw InputError(file + ": contact_pressure_MPa applies to the knee pairs only (uhmwpe-cocr, "
                       "peek-cocr, cfrpeek-cocr), not to " + pair_name(pair));
    }
    p.pressure = 1e6 * r.number("", "contact_pressure_MPa", 0.0, 0.1, 10000.0);
    p.source = "contact_pressure_MPa of " + file;
  } else {
    r.find("", "contact_pressure_MPa");
    if (is_knee_pair(pair) && knee_pressure) p = knee_pressure(pair);
  }
  ParticleModelConfig c = make_pair_config(pair, p.pressure, p.source);
  r.set("", "load_N", c.load, 1.0, 0.0, 1e6);
  r.set("", "friction", c.friction, 1.0, 0.0, 2.0);
  r.set("", "cylinder_radius_mm", c.cylinder_radius, 1e-3, 1e-6, 1e6);
  r.set("", "cylinder_length_mm", c.cylinder_length, 1e-3, 1e-6, 1e6);
  r.flag("", "plastic_deformation", c.plastic_deformation);
  // grid sizes are checked against memory by check_grid when the run starts
  r.set_int("grid", "nx", c.grid.nx, -1e9, 1e9);
  r.set_int("grid", "ny", c.grid.ny, -1e9, 1e9);
  r.set("grid", "dx_nm", c.grid.dx, 1e-9, -1e9, 1e9);
  c.grid.dy = c.grid.dx;
  r.set_int("grid", "nz", c.nz, -1e9, 1e9);
  r.set("grid", "dz_nm", c.dz, 1e-9, 1e-6, 1e9);
  r.set_int("grid", "refine", c.refine, 1, 16);
  r.set_int("run", "min_iterations", c.min_iterations, 0, 1e6);  // 0 = automatic
  r.set_int("run", "max_iterations", c.max_iterations, 0, 1e6);  // 0 = automatic
  r.set_int("run", "block", c.block, 0, 1e6);  // 0 = automatic
  r.set_int("run", "slide_cells", c.slide_cells, 0, 1e9);
  r.set_int("run", "track_factor", c.track_factor, 1, 64);
  r.set("run", "steady_tolerance", c.steady_tolerance, 1.0, 0.0, 10.0);
  r.set("run", "roughness_tolerance", c.roughness_tolerance, 1.0, 0.0, 10.0);
  r.set_int("run", "contact_max_iterations", c.contact_max_iterations, 1, 100000);
  read_body(r, "harder", c.harder);
  read_body(r, "softer", c.softer);
  r.reject_unread();
  return c;
}

}  // namespace kneesim::particles
