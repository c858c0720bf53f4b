#include "wear/particles/particles_config.h"

#include <cstdio>
#include <set>

#include "engine/errors.h"
#include "tools/io/toml_file.h"

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
  std::string text(const std::string& section, const std::string& key,
                   const std::string& fallback) const {
    const io::TomlEntry* e = find(section, key);
    if (e == nullptr) return fallback;
    const std::string* v = std::get_if<std::string>(&e->value);
    if (!v) throw InputError(where(section, key, *e) + " = " + io::describe(e->value) + " must be a string");
    return *v;
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
  b.elastic.youngs_modulus = 1e9 * r.number(s, "E_GPa", b.elastic.youngs_modulus / 1e9, 1e-4, 2000);
  b.elastic.poisson_ratio = r.number(s, "nu", b.elastic.poisson_ratio, 0.0, 0.499);
  b.hardness = 1e9 * r.number(s, "hardness_GPa", b.hardness / 1e9, 1e-5, 100);
  b.yield_stress = 1e9 * r.number(s, "yield_GPa", b.yield_stress / 1e9, 1e-5, 100);
  b.roughness.rq = 1e-9 * r.number(s, "rq_nm", b.roughness.rq * 1e9, 1e-3, 1e5);
  b.roughness.skewness = r.number(s, "skewness", b.roughness.skewness, -5, 5);
  b.roughness.kurtosis = r.number(s, "kurtosis", b.roughness.kurtosis, 1.0, 50);
  b.roughness.correlation_length =
      1e-9 * r.number(s, "correlation_length_nm", b.roughness.correlation_length * 1e9, 1e-3, kBig);
  b.roughness.lambda_s = 1e-9 * r.number(s, "lambda_s_nm", b.roughness.lambda_s * 1e9, 0.0, 1e9);
  b.roughness.seed = static_cast<std::uint64_t>(r.number(s, "seed", double(b.roughness.seed), 0, 1e15));
  b.elastic.film_thickness =
      1e-9 * r.number(s, "film_thickness_nm", b.elastic.film_thickness * 1e9, 0.0, 1e6);
  b.elastic.film_modulus = 1e9 * r.number(s, "film_E_GPa", b.elastic.film_modulus / 1e9, 0.0, 2000);
  b.elastic.film_poisson = r.number(s, "film_nu", b.elastic.film_poisson, 0.0, 0.499);
  if (b.elastic.film_thickness > 0.0 && !(b.elastic.film_modulus > 0.0)) {
    throw InputError(r.file + ": [" + s + "] film_E_GPa must be > 0 when film_thickness_nm > 0");
  }
  b.surface_csv = r.text(s, "surface_csv", b.surface_csv);
}

}  // namespace

ParticleModelConfig read_particle_config(const std::filesystem::path& path) {
  const std::string file = path.string();
  const io::TomlDocument doc = io::read_toml_file(path);
  const Reader r{file, doc, {}};
  ParticleModelConfig c = make_pair_config(parse_pair(r.text("", "pair", "steel-steel"), file + ": pair"));
  c.load = r.number("", "load_N", c.load, 0.0, 1e6);
  c.friction = r.number("", "friction", c.friction, 0.0, 2.0);
  c.cylinder_radius = 1e-3 * r.number("", "cylinder_radius_mm", c.cylinder_radius * 1e3, 1e-6, 1e6);
  c.cylinder_length = 1e-3 * r.number("", "cylinder_length_mm", c.cylinder_length * 1e3, 1e-6, 1e6);
  // grid sizes are checked against memory by check_grid when the run starts
  c.grid.nx = static_cast<int>(r.number("grid", "nx", c.grid.nx, -1e9, 1e9));
  c.grid.ny = static_cast<int>(r.number("grid", "ny", c.grid.ny, -1e9, 1e9));
  c.grid.dx = c.grid.dy = 1e-9 * r.number("grid", "dx_nm", c.grid.dx * 1e9, -1e9, 1e9);
  c.nz = static_cast<int>(r.number("grid", "nz", c.nz, -1e9, 1e9));
  c.dz = 1e-9 * r.number("grid", "dz_nm", c.dz * 1e9, 1e-6, 1e9);
  c.refine = static_cast<int>(r.number("grid", "refine", c.refine, 1, 16));
  c.min_iterations = static_cast<int>(r.number("run", "min_iterations", c.min_iterations, 1, 1e6));
  c.max_iterations = static_cast<int>(r.number("run", "max_iterations", c.max_iterations, 1, 1e6));
  c.block = static_cast<int>(r.number("run", "block", c.block, 1, 1e6));
  c.slide_cells = static_cast<int>(r.number("run", "slide_cells", c.slide_cells, 0, 1e9));
  c.track_factor = static_cast<int>(r.number("run", "track_factor", c.track_factor, 1, 64));
  c.steady_tolerance = r.number("run", "steady_tolerance", c.steady_tolerance, 0.0, 10.0);
  read_body(r, "harder", c.harder);
  read_body(r, "softer", c.softer);
  r.reject_unread();
  return c;
}

}  // namespace kneesim::particles
