// The configuration reference is generated from the config registry; docs/config-reference.md
// must be the current build's output (regenerate with
// `build/tools/kneesim config --reference > docs/config-reference.md`).
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "engine/io/source_tree.h"
#include "models/config.h"
#include "models/config_reference.h"

using namespace kneesim::models;

TEST_CASE("docs/config-reference.md equals the build's configuration reference") {
  const std::string path = (kneesim::io::source_dir() / "docs/config-reference.md").string();
  std::ifstream in(path);
  REQUIRE_MESSAGE(in.good(), path << " is missing");
  std::stringstream text;
  text << in.rdbuf();
  const bool same = text.str() == config_reference_markdown();
  CHECK_MESSAGE(same, path << " differs from `kneesim config --reference`; regenerate it with "
                "`build/tools/kneesim config --reference > docs/config-reference.md`");
}

TEST_CASE("every config key has a type, an allowed range, a meaning and a default") {
  const auto keys = config_reference();
  CHECK(keys.size() > 100);
  std::set<std::string> seen;
  for (const auto& k : keys) {
    INFO(k.key);
    CHECK(seen.insert(k.key).second);
    CHECK(!k.type.empty());
    CHECK(!k.allowed.empty());
    CHECK(k.meaning.size() > 10);
    CHECK(!k.default_value.empty());
  }
}

TEST_CASE("the reference's defaults are the values a config without that key gets") {
  // reference: load_config with no file is the default config; each number key's listed
  // default must be what find_number_key reads from it
  // (the law as specified: a calibrated law writes its K_eff into contact.foundation_modulus_MPa,
  // models/contact_law_library.h; contact.calibration is a choice, not compared here)
  const Config c = load_config("", {{"contact.calibration", "\"off\""}});
  for (const auto& k : config_reference()) {
    const auto n = find_number_key(c, k.key);
    if (!n) continue;
    INFO(k.key);
    // printed with 12 significant digits: equal to 1e-11 relative
    CHECK(std::abs(std::stod(k.default_value) - n->value) <= 1e-11 * std::abs(n->value));
  }
  // a preset default differs where the preset sets it: the materials_study restraint
  bool found = false;
  for (const auto& k : config_reference()) {
    if (k.key != "rig.restraint.k_ie_Nm_per_deg") continue;
    for (const auto& [preset, value] : k.preset_defaults)
      if (preset == "materials_study") found = value == "0.3";
  }
  CHECK(found);
}
