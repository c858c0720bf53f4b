// The particle model's TOML input (wear/particles/particles_config.h). References: the values
// written in the file override the pair preset and nothing else does; the design.md error
// contract (one sentence naming file, line, key, value and range) for the bad inputs tried.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "engine/errors.h"
#include "tests/loads/input_error.h"
#include "tests/loads/temp_dir.h"
#include "wear/particles/particles_config.h"

using kneesim::InputError;
using kneesim::test::TempDir;
namespace pt = kneesim::particles;

namespace {

std::string error_of(const std::filesystem::path& file) {
  return kneesim::test::input_error_message([&] { pt::read_particle_config(file); });
}

}  // namespace

TEST_CASE("particle config: the file overrides the preset, in SI inside") {
  TempDir tmp;
  const auto f = tmp.write("p.toml",
                           "pair = \"steel-steel\"\nload_N = 2.5\n"
                           "[grid]\nnx = 128\nny = 96\ndx_nm = 150\n"
                           "[softer]\nrq_nm = 300\n");
  const pt::ParticleModelConfig c = pt::read_particle_config(f);
  const pt::ParticleModelConfig preset = pt::make_pair_config(pt::parse_pair("steel-steel", "t"));
  CHECK(c.load == 2.5);
  CHECK(c.grid.nx == 128);
  CHECK(c.grid.ny == 96);
  CHECK(c.grid.dx == doctest::Approx(150e-9).scale(0));
  CHECK(c.softer.roughness.rq == doctest::Approx(300e-9).scale(0));
  CHECK(c.harder.roughness.rq == preset.harder.roughness.rq);
  CHECK(c.friction == preset.friction);
}

TEST_CASE("particle config: bad input names file, line and key") {
  TempDir tmp;
  const std::string range = error_of(tmp.write("a.toml", "pair = \"steel-steel\"\nfriction = 3\n"));
  CHECK(range.find("a.toml:2") != std::string::npos);
  CHECK(range.find("friction") != std::string::npos);
  CHECK(range.find("allowed range") != std::string::npos);
  const std::string unknown = error_of(tmp.write("b.toml", "[harder]\nrq = 50\n"));
  CHECK(unknown.find("b.toml:2") != std::string::npos);
  CHECK(unknown.find("harder.rq") != std::string::npos);
  const std::string type = error_of(tmp.write("c.toml", "load_N = \"ten\"\n"));
  CHECK(type.find("load_N") != std::string::npos);
  CHECK(type.find("number") != std::string::npos);
  const std::string pair = error_of(tmp.write("d.toml", "pair = \"steel-wood\"\n"));
  CHECK(pair.find("steel-wood") != std::string::npos);
}

TEST_CASE("particle config: the lay (peklenik_gamma) overrides the preset and is range-checked") {
  TempDir tmp;
  const pt::ParticleModelConfig c =
      pt::read_particle_config(tmp.write("g.toml", "[softer]\npeklenik_gamma = 1\n"));
  const pt::ParticleModelConfig preset = pt::make_pair_config(pt::parse_pair("steel-steel", "t"));
  CHECK(c.softer.roughness.gamma == 1.0);
  CHECK(c.harder.roughness.gamma == preset.harder.roughness.gamma);
  const std::string bad = error_of(tmp.write("h.toml", "[harder]\npeklenik_gamma = 0\n"));
  CHECK(bad.find("h.toml:2") != std::string::npos);
  CHECK(bad.find("peklenik_gamma") != std::string::npos);
}

TEST_CASE("particle config: plastic_deformation is a boolean, roughness_tolerance a range-checked number") {
  TempDir tmp;
  const pt::ParticleModelConfig c = pt::read_particle_config(
      tmp.write("k.toml", "plastic_deformation = false\n[run]\nroughness_tolerance = 0.05\n"));
  CHECK_FALSE(c.plastic_deformation);
  CHECK(c.roughness_tolerance == 0.05);
  CHECK(pt::make_pair_config(pt::PairName::kSteelSteel).plastic_deformation);
  const std::string type = error_of(tmp.write("l.toml", "plastic_deformation = 1\n"));
  CHECK(type.find("l.toml:1") != std::string::npos);
  CHECK(type.find("true or false") != std::string::npos);
  const std::string range = error_of(tmp.write("m.toml", "[run]\nroughness_tolerance = -1\n"));
  CHECK(range.find("roughness_tolerance") != std::string::npos);
}

TEST_CASE("particle config: a transfer film needs its yield stress") {
  TempDir tmp;
  const std::string missing = error_of(tmp.write(
      "f.toml", "pair = \"steel-steel\"\n[harder]\nfilm_thickness_nm = 300\nfilm_E_GPa = 88\n"));
  CHECK(missing.find("film_yield_GPa") != std::string::npos);
  const pt::ParticleModelConfig c = pt::read_particle_config(tmp.write(
      "g.toml", "pair = \"steel-steel\"\n[harder]\nfilm_thickness_nm = 300\nfilm_E_GPa = 88\n"
                "film_yield_GPa = 0.5\n"));
  CHECK(c.harder.film_yield_stress == doctest::Approx(0.5e9));
}

// Reference: the flow rule's film hardness (particle_model.h): given, or 2.8 x the film's yield
// stress (the study's H = 2.8 sigma_y); the brass preset's film is the disk's brass (2.64 GPa).
TEST_CASE("particle config: film hardness and contact iterations") {
  TempDir tmp;
  CHECK(pt::make_pair_config(pt::PairName::kSteelBrass).harder.film_hardness == 2.64e9);
  const pt::ParticleModelConfig c = pt::read_particle_config(tmp.write(
      "h.toml", "pair = \"steel-steel\"\n[harder]\nfilm_thickness_nm = 300\nfilm_E_GPa = 88\n"
                "film_yield_GPa = 0.5\n[run]\ncontact_max_iterations = 200\n"));
  CHECK(c.harder.film_hardness == 0.0);
  CHECK(pt::counterface_flow_hardness(c.harder) == doctest::Approx(1.4e9));
  CHECK(c.contact_max_iterations == 200);
  const pt::ParticleModelConfig d = pt::read_particle_config(tmp.write(
      "i.toml", "pair = \"steel-brass\"\n[harder]\nfilm_hardness_GPa = 2.0\n"));
  CHECK(pt::counterface_flow_hardness(d.harder) == doctest::Approx(2.0e9));
  pt::BodySpec bare = d.harder;
  bare.elastic.film_thickness = 0.0;  // no film: the counterface's own hardness
  CHECK(pt::counterface_flow_hardness(bare) == 6e9);
  const std::string bad = error_of(tmp.write("j.toml", "[run]\ncontact_max_iterations = 0\n"));
  CHECK(bad.find("j.toml:2") != std::string::npos);
  CHECK(bad.find("contact_max_iterations") != std::string::npos);
  const std::string neg = error_of(tmp.write("k.toml", "[harder]\nfilm_hardness_GPa = -1\n"));
  CHECK(neg.find("film_hardness_GPa") != std::string::npos);
}

TEST_CASE("particle config: a knee pair's contact pressure sizes the cylinder (Hertz)") {
  // reference: the Hertz line contact (Johnson 1985, eq. 4.45): peak p0 = sqrt(w E* / (pi R))
  // for a load w per unit length and 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2; the pair sizes
  // R and the load so that p0 is the given contact pressure (tolerance 1e-12 relative)
  TempDir tmp;
  const auto f = tmp.write("k.toml", "pair = \"peek-cocr\"\ncontact_pressure_MPa = 23.6\n");
  const pt::ParticleModelConfig c = pt::read_particle_config(f);
  CHECK(c.contact_pressure == doctest::Approx(23.6e6).epsilon(1e-15));
  CHECK(c.contact_pressure_source.find("k.toml") != std::string::npos);
  const double e_star =
      1.0 / ((1.0 - 0.3 * 0.3) / 230e9 + (1.0 - 0.3 * 0.3) / 3500e6);  // CoCr on PEEK
  const double w = c.load / c.cylinder_length;
  CHECK(std::sqrt(w * e_star / (3.14159265358979323846 * c.cylinder_radius)) ==
        doctest::Approx(23.6e6).epsilon(1e-12));
  // without the key the caller's source is used (kneesim particles: a kneesim contact run)
  const auto g = tmp.write("g.toml", "pair = \"uhmwpe-cocr\"\n");
  const pt::ParticleModelConfig d = pt::read_particle_config(
      g, [](pt::PairName) { return pt::KneeContactPressure{30.6e6, "a contact run"}; });
  CHECK(d.contact_pressure == 30.6e6);
  CHECK(d.sources.find("a contact run") != std::string::npos);
}

TEST_CASE("particle config: contact pressure missing for a knee pair, or given for another") {
  TempDir tmp;
  const std::string missing = error_of(tmp.write("m.toml", "pair = \"cfrpeek-cocr\"\n"));
  CHECK(missing.find("cfrpeek-cocr") != std::string::npos);
  CHECK(missing.find("contact pressure") != std::string::npos);
  const std::string other =
      error_of(tmp.write("o.toml", "pair = \"steel-steel\"\ncontact_pressure_MPa = 20\n"));
  CHECK(other.find("contact_pressure_MPa") != std::string::npos);
  CHECK(other.find("steel-steel") != std::string::npos);
}
