// Calibrated contact-law files (models/contact_law_file.h): written and read back; a malformed
// file, a value out of range, or a law for another material or implant is refused with one
// sentence naming the file, the key and the value; a config naming the file takes its modulus.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "engine/errors.h"
#include "models/build_model.h"
#include "models/config.h"
#include "models/contact_law_file.h"

using namespace kneesim;
using namespace kneesim::models;

namespace {

std::filesystem::path temp_file(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / ("kneesim_law_" + name);
  std::ofstream(p) << text;
  return p;
}

}  // namespace

TEST_CASE("contact law file: round trip, and refusals naming file, key and value") {
  CalibratedContactLaw law;
  law.material = "uhmwpe";
  law.implant = "generic";
  law.foundation_modulus_MPa = 812.5;
  law.specified_modulus_MPa = 4170.0;
  law.fitted_on = "test";
  const auto good = std::filesystem::temp_directory_path() / "kneesim_law_good.toml";
  write_contact_law_file(good, law);
  const CalibratedContactLaw back = read_contact_law_file(good, "uhmwpe", "generic");
  CHECK(back.foundation_modulus_MPa == 812.5);
  CHECK(back.law == "nonlinear");

  CHECK_THROWS_WITH_AS(read_contact_law_file(good, "peek", "generic"),
                       doctest::Contains("calibrated for material \"uhmwpe\", the config's "
                                         "material.name is \"peek\""),
                       InputError);
  CHECK_THROWS_WITH_AS(read_contact_law_file(good, "uhmwpe", "/x/insert.stl"),
                       doctest::Contains("calibrated for implant \"generic\""), InputError);
  const auto syntax = temp_file("syntax.toml", "[calibrated_contact\nmaterial = 1\n");
  const std::string syntax_name = syntax.string();
  CHECK_THROWS_WITH_AS(read_contact_law_file(syntax, "uhmwpe", "generic"),
                       doctest::Contains(syntax_name.c_str()), InputError);
  const auto missing = temp_file("missing.toml", "[calibrated_contact]\nmaterial = \"uhmwpe\"\n");
  CHECK_THROWS_WITH_AS(read_contact_law_file(missing, "uhmwpe", "generic"),
                       doctest::Contains("lacks the key 'calibrated_contact.implant'"), InputError);
  const auto negative = temp_file(
      "negative.toml",
      "[calibrated_contact]\nmaterial = \"uhmwpe\"\nimplant = \"generic\"\nlaw = \"nonlinear\"\n"
      "foundation_modulus_MPa = -3\nspecified_modulus_MPa = 4170\n");
  const std::string negative_text = negative.string() +
                                    ":5: key 'calibrated_contact.foundation_modulus_MPa' = -3 "
                                    "is outside the allowed range";
  CHECK_THROWS_WITH_AS(read_contact_law_file(negative, "uhmwpe", "generic"),
                       doctest::Contains(negative_text.c_str()), InputError);
  CHECK_THROWS_WITH_AS(read_contact_law_file("/nonexistent/law.toml", "uhmwpe", "generic"),
                       doctest::Contains("not found"), InputError);

  // a config naming the file uses its modulus; of another material it is refused
  const Config c = load_config({}, {{"contact.law_file", "\"" + good.string() + "\""}});
  CHECK(c.contact_foundation_modulus_MPa == 812.5);
  const BuiltModel built = build_model(c);
  CHECK(built.model.contact.foundation_modulus == doctest::Approx(812.5e6));
  CHECK_THROWS_AS(load_config({}, {{"contact.law_file", "\"" + good.string() + "\""},
                                   {"material.name", "\"peek\""}}),
                  InputError);
}
