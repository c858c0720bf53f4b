// The toml++ adapter (engine/io/toml_file.h) and the config reader on top of it. References:
// the TOML text written in each case (keys, values, the line each sits on), and the error
// contract of design.md: one sentence naming the file and line (or key) of the bad input.
#include <doctest/doctest.h>

#include <string>

#include "engine/errors.h"
#include "engine/io/toml_file.h"
#include "models/config.h"
#include "temp_dir.h"
#include "tests/loads/input_error.h"

using kneesim::InputError;
using kneesim::test::TempDir;
namespace io = kneesim::io;

using kneesim::test::input_error_message;

TEST_CASE("TOML documents flatten to dotted keys with their lines") {
  TempDir tmp;
  const auto f = tmp.write("a.toml",
                           "top = 3\n"
                           "[rig.restraint]\n"
                           "gap_mm = 2.5\n"
                           "on = true\n"
                           "name = \"x\"\n"
                           "list = [1, 2.5]\n"
                           "words = [\"a=1\", \"b=2\"]\n");
  const io::TomlDocument doc = io::read_toml_file(f);
  REQUIRE(doc.size() == 6);
  CHECK(std::get<double>(doc.at("top").value) == 3.0);
  CHECK(doc.at("top").line == 1);
  CHECK(std::get<double>(doc.at("rig.restraint.gap_mm").value) == 2.5);
  CHECK(doc.at("rig.restraint.gap_mm").line == 3);
  CHECK(std::get<bool>(doc.at("rig.restraint.on").value));
  CHECK(std::get<std::string>(doc.at("rig.restraint.name").value) == "x");
  CHECK(std::get<std::vector<double>>(doc.at("rig.restraint.list").value) ==
        std::vector<double>{1.0, 2.5});
  CHECK(std::get<std::vector<std::string>>(doc.at("rig.restraint.words").value) ==
        std::vector<std::string>{"a=1", "b=2"});
}

TEST_CASE("TOML errors name the file and the line") {
  TempDir tmp;
  const auto bad = tmp.write("bad.toml", "a = 1\nb = = 2\n");
  const std::string syntax = input_error_message([&] { io::read_toml_file(bad); });
  CHECK(syntax.find("bad.toml:2") != std::string::npos);
  const auto mixed = tmp.write("mixed.toml", "\n\nm = [1, \"two\"]\n");
  const std::string m = input_error_message([&] { io::read_toml_file(mixed); });
  CHECK(m.find("mixed.toml:3") != std::string::npos);
  CHECK(m.find("'m'") != std::string::npos);
  const std::string missing = input_error_message([&] { io::read_toml_file(tmp.path / "none.toml"); });
  CHECK(missing.find("none.toml") != std::string::npos);
}

TEST_CASE("values given on the command line parse as TOML, bare words as strings") {
  CHECK(std::get<double>(io::parse_toml_value("2.5")) == 2.5);
  CHECK(std::get<bool>(io::parse_toml_value("false")) == false);
  CHECK(std::get<std::string>(io::parse_toml_value("peek")) == "peek");
  CHECK(std::get<std::string>(io::parse_toml_value("\"cfr peek\"")) == "cfr peek");
  CHECK(std::get<std::vector<double>>(io::parse_toml_value("[1, 2]")).size() == 2);
  // an empty array has no element type; it serves as an empty string list
  REQUIRE(io::as_string_list(io::parse_toml_value("[]")) != nullptr);
  CHECK(io::as_string_list(io::parse_toml_value("[]"))->empty());
  CHECK(io::as_string_list(io::parse_toml_value("[1]")) == nullptr);
}

TEST_CASE("config: an out-of-range value names the file and line; materials and conditions") {
  TempDir tmp;
  const auto f = tmp.write("run.toml",
                           "[contact]\n"
                           "friction = 1.5\n");
  const std::string e = input_error_message([&] { kneesim::models::load_config(f, {}); });
  CHECK(e.find("run.toml:2") != std::string::npos);
  CHECK(e.find("contact.friction") != std::string::npos);

  const auto g = tmp.write("mat.toml",
                           "[material]\nname = \"soft\"\n"
                           "[materials.soft]\nelastic_modulus_MPa = 500\npoisson = 0.45\n"
                           "[conditions.high]\nset = [\"contact.friction=0.05\"]\n"
                           "[conditions.as_configured]\nset = []\n");
  const auto c = kneesim::models::load_config(g, {});
  CHECK(c.material.name == "soft");
  CHECK(c.user_materials.at("soft").elastic_modulus_MPa == 500.0);
  REQUIRE(c.conditions.count("high") == 1);
  CHECK(c.conditions.at("high") == std::vector<std::string>{"contact.friction=0.05"});
  REQUIRE(c.conditions.count("as_configured") == 1);  // an empty list: the config as it is
  CHECK(c.conditions.at("as_configured").empty());

  const auto h = tmp.write("cond.toml", "[conditions.high]\nset = [\"no equals sign\"]\n");
  const std::string ce = input_error_message([&] { kneesim::models::load_config(h, {}); });
  CHECK(ce.find("cond.toml:2") != std::string::npos);
  CHECK(ce.find("key=value") != std::string::npos);
}
