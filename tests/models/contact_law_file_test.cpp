// Calibrated contact-law files (models/contact_law_file.h) and their key
// (models/contact_law_key.h): written and read back with the provenance; a malformed file or a
// value out of range is refused with one sentence naming the file, the key and the value; a
// law of another material (name or constants) or another implant (another geometry, or the
// same mesh path with other content) is refused naming the file and what differs; a config
// naming the file takes its modulus.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "engine/errors.h"
#include "models/build_model.h"
#include "models/config.h"
#include "models/contact_law_file.h"
#include "models/contact_law_key.h"
#include "models/contact_law_library.h"

using namespace kneesim;
using namespace kneesim::models;

namespace {

std::filesystem::path temp_file(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / ("kneesim_law_" + name);
  std::ofstream(p) << text;
  return p;
}

Config load(std::vector<Override> o) {
  o.push_back({"contact.calibration", "\"off\""});  // these tests look at files, not libraries
  return load_config({}, o);
}

}  // namespace

TEST_CASE("contact law key: what changes it and what does not") {
  const ContactLawKey base = make_contact_law_key(load({}));
  // the implant, the material's constants and the [deformable] reference change it
  const ContactLawKey thicker = make_contact_law_key(load({{"implant.generic.insert_thickness_mm", "9"}}));
  CHECK(thicker.implant != base.implant);
  CHECK(thicker.material == base.material);
  CHECK(thicker.key != base.key);
  const ContactLawKey stiffer = make_contact_law_key(load({{"material.elastic_modulus_MPa", "700"}}));
  CHECK(stiffer.material != base.material);
  CHECK(stiffer.implant == base.implant);
  CHECK(stiffer.key != base.key);
  const ContactLawKey mesh = make_contact_law_key(load({{"deformable.element_size_mm", "0.7"}}));
  CHECK(mesh.settings != base.settings);
  CHECK(mesh.key != base.key);
  // the loading, the friction override and the rigid path's discretization do not
  for (const Override& o : std::vector<Override>{{"rig.preset", "\"materials_study\""},
                                                 {"contact.friction", "0.1"},
                                                 {"implant.edge_length_mm", "2"},
                                                 {"gait.period_s", "0.2"},
                                                 {"rig.alignment.insert_tilt_deg", "1"}}) {
    CAPTURE(o.key);
    CHECK(make_contact_law_key(load({o})).key == base.key);
  }
}

TEST_CASE("contact law key: an imported implant hashes its mesh files' content") {
  const auto dir = std::filesystem::temp_directory_path() / "kneesim_law_mesh";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "femur.stl") << "solid a\nendsolid a\n";
  std::ofstream(dir / "insert.stl") << "solid b\nendsolid b\n";
  const std::vector<Override> mesh = {{"implant.kind", "\"mesh\""},
                                      {"implant.mesh.femur", "\"" + (dir / "femur.stl").string() + "\""},
                                      {"implant.mesh.insert", "\"" + (dir / "insert.stl").string() + "\""}};
  const ContactLawKey before = make_contact_law_key(load(mesh));
  std::ofstream(dir / "insert.stl") << "solid c\nendsolid c\n";  // same path, other content
  std::filesystem::last_write_time(dir / "insert.stl",
                                   std::filesystem::last_write_time(dir / "insert.stl") +
                                       std::chrono::seconds(5));
  const ContactLawKey after = make_contact_law_key(load(mesh));
  CHECK(after.implant != before.implant);
  CHECK(after.material == before.material);
  std::filesystem::remove_all(dir);
}

TEST_CASE("contact law file: round trip, and refusals naming file, key and value") {
  const Config config = load({});
  CalibratedContactLaw law;
  law.material = "uhmwpe";
  law.implant = "generic";
  law.key = make_contact_law_key(config);
  // values a fit gives (not short binary fractions): the file must hand back the same doubles,
  // or a run that calibrates on first use and a later run reading the cached file would differ
  law.foundation_modulus_MPa = 396.9947397196232;
  law.exponent = 0.6283185307179586;
  law.specified_modulus_MPa = 4170.0;
  law.fitted_on = "test";
  law.provenance = {{"command", "\"kneesim calibrate-contact\""}, {"held_out_peak_rms_calibrated", "0.05"}};
  const auto good = std::filesystem::temp_directory_path() / "kneesim_law_good.toml";
  write_contact_law_file(good, law);
  const CalibratedContactLaw back = read_contact_law_file(good);
  CHECK(back.foundation_modulus_MPa == law.foundation_modulus_MPa);
  CHECK(back.exponent == law.exponent);
  CHECK(back.law == "nonlinear");
  CHECK(back.key.key == law.key.key);
  REQUIRE(back.provenance.size() == 2);
  CHECK(back.provenance[0].second == "\"kneesim calibrate-contact\"");
  CHECK_NOTHROW(check_contact_law_fits(good, back, "uhmwpe", "generic", law.key));

  CHECK_THROWS_WITH_AS(check_contact_law_fits(good, back, "peek", "generic", law.key),
                       doctest::Contains("calibrated for material \"uhmwpe\", the config's "
                                         "material.name is \"peek\""),
                       InputError);
  ContactLawKey other = law.key;
  other.material = "0123456789abcdef";
  CHECK_THROWS_WITH_AS(check_contact_law_fits(good, back, "uhmwpe", "generic", other),
                       doctest::Contains("with other constants"), InputError);
  other = law.key;
  other.implant = "0123456789abcdef";
  CHECK_THROWS_WITH_AS(check_contact_law_fits(good, back, "uhmwpe", "generic", other),
                       doctest::Contains("its meshes or placement changed since"), InputError);
  CHECK_THROWS_WITH_AS(check_contact_law_fits(good, back, "uhmwpe", "/x/insert.stl", other),
                       doctest::Contains("calibrated for implant \"generic\""), InputError);

  const auto syntax = temp_file("syntax.toml", "[calibrated_contact\nmaterial = 1\n");
  const std::string syntax_name = syntax.string();
  CHECK_THROWS_WITH_AS(read_contact_law_file(syntax), doctest::Contains(syntax_name.c_str()),
                       InputError);
  const auto missing = temp_file("missing.toml", "[calibrated_contact]\nmaterial = \"uhmwpe\"\n");
  CHECK_THROWS_WITH_AS(read_contact_law_file(missing),
                       doctest::Contains("lacks the key 'calibrated_contact.implant'"), InputError);
  const auto negative = temp_file(
      "negative.toml",
      "[calibrated_contact]\nmaterial = \"uhmwpe\"\nimplant = \"generic\"\nkey = \"a\"\n"
      "implant_hash = \"b\"\nmaterial_hash = \"c\"\nsettings_hash = \"d\"\nlaw = \"nonlinear\"\n"
      "foundation_modulus_MPa = -3\nspecified_modulus_MPa = 4170\n");
  const std::string negative_text = negative.string() +
                                    ":9: key 'calibrated_contact.foundation_modulus_MPa' = -3 "
                                    "is outside the allowed range";
  CHECK_THROWS_WITH_AS(read_contact_law_file(negative), doctest::Contains(negative_text.c_str()),
                       InputError);
  // an exponent outside 0.2-2 (the law would not be a foundation's): refused, naming the value
  const auto steep = temp_file(
      "steep.toml",
      "[calibrated_contact]\nmaterial = \"uhmwpe\"\nimplant = \"generic\"\nkey = \"a\"\n"
      "implant_hash = \"b\"\nmaterial_hash = \"c\"\nsettings_hash = \"d\"\nlaw = \"nonlinear\"\n"
      "foundation_modulus_MPa = 300\nexponent = 5\nspecified_modulus_MPa = 4170\n");
  CHECK_THROWS_WITH_AS(read_contact_law_file(steep),
                       doctest::Contains("key 'calibrated_contact.exponent' = 5 is outside the allowed range"),
                       InputError);
  const auto unknown = temp_file("unknown.toml", "[calibrated_contact]\nmodulus = 3\n");
  CHECK_THROWS_WITH_AS(read_contact_law_file(unknown),
                       doctest::Contains("unknown key 'calibrated_contact.modulus'"), InputError);
  CHECK_THROWS_WITH_AS(read_contact_law_file("/nonexistent/law.toml"), doctest::Contains("not found"),
                       InputError);

  // a config naming the file uses its modulus; of another material it is refused
  const Config c = load_config({}, {{"contact.law_file", "\"" + good.string() + "\""}});
  CHECK(c.contact_foundation_modulus_MPa == law.foundation_modulus_MPa);
  CHECK(c.contact_law_resolution.source == "law_file");
  const BuiltModel built = build_model(c);
  CHECK(built.model.contact.foundation_modulus == doctest::Approx(law.foundation_modulus_MPa * 1e6));
  CHECK_THROWS_AS(load_config({}, {{"contact.law_file", "\"" + good.string() + "\""},
                                   {"material.name", "\"peek\""}}),
                  InputError);
}

TEST_CASE("contact law resolution: the shipped law of the built-in implant by default, a stated fallback otherwise") {
  // every shipped law is the law of the default config of its material: a changed default
  // ([deformable], a material's constants, the generic implant) makes it stale, and this names
  // the file to regenerate (tools/scripts/calibrate_contact_laws.sh)
  for (const auto& [file, law] : shipped_contact_laws()) {
    CAPTURE(file);
    if (law.implant != "generic") continue;
    const Config c = load_config({}, {{"material.name", "\"" + law.material + "\""}});
    CHECK(make_contact_law_key(make_calibration_config(c)).key == law.key.key);
  }
  for (const char* material : {"uhmwpe", "peek", "cfr-peek"}) {
    CAPTURE(material);
    const Config c = load_config({}, {{"material.name", std::string("\"") + material + "\""}});
    const ContactLawResolution& r = c.contact_law_resolution;
    CHECK(r.source == "library");
    CHECK(std::filesystem::path(r.file).filename() == std::string("generic_") + material + ".toml");
    CHECK(r.warning.empty());
    const CalibratedContactLaw law = read_contact_law_file(r.file);
    CHECK(c.contact_foundation_modulus_MPa == law.foundation_modulus_MPa);
    CHECK(c.contact_law_exponent == law.exponent);
    CHECK(law.foundation_modulus_MPa != doctest::Approx(law.specified_modulus_MPa).epsilon(0.01));
    bool has_command = false;
    for (const auto& [k, v] : r.provenance) has_command |= k == "command";
    CHECK(has_command);
    // the rigid model runs with it
    const BuiltModel b = build_model(load_config({}, {{"material.name", std::string("\"") + material + "\""},
                                                       {"implant.edge_length_mm", "3"}}));
    CHECK(b.model.contact.foundation_modulus == doctest::Approx(law.foundation_modulus_MPa * 1e6));
    CHECK(b.model.contact.exponent == law.exponent);
  }
  // --no-calibrate: the law as specified, with the warning
  const Config off = load_config({}, {{"contact.calibration", "\"off\""}});
  CHECK(off.contact_law_resolution.source == "specified");
  CHECK(off.contact_foundation_modulus_MPa == 0.0);
  CHECK(off.contact_law_resolution.warning.find("contact law as specified") != std::string::npos);
  // no law for these material constants, auto: the stated fallback (the law as specified, warning)
  const Config other = load_config({}, {{"material.elastic_modulus_MPa", "700"},
                                        {"contact.calibration", "\"auto\""}});
  CHECK(other.contact_law_resolution.source == "specified");
  CHECK(other.contact_law_resolution.warning.find("no calibrated contact law") != std::string::npos);
  // first_use (the default) without the calibration having run: a rigid model is refused,
  // never inflated
  CHECK(load_config({}, {}).contact_calibration == "first_use");
  const Config first = load_config({}, {{"material.elastic_modulus_MPa", "700"}});
  CHECK(first.contact_law_resolution.needs_calibration);
  CHECK_THROWS_WITH_AS(build_model(first), doctest::Contains("no calibrated contact law"), InputError);
  // a shipped law named for another material: refused, naming the file
  const std::string uhmwpe_law = (shipped_contact_law_dir() / "generic_uhmwpe.toml").string();
  CHECK_THROWS_WITH_AS(load_config({}, {{"contact.law_file", "\"" + uhmwpe_law + "\""},
                                        {"material.name", "\"peek\""}}),
                       doctest::Contains(uhmwpe_law.c_str()), InputError);
}
