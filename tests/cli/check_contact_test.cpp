// `kneesim check-contact` end to end on a coarse case (3 mm elements, 3 layers from a config
// file, the iso rig preset, which the shipped UHMWPE law was not fitted on): it writes the comparison, the
// summary, the plot and the report and prints the table. References: the shipped law's
// modulus is 0.35 times the specified one (models/contact_laws/generic_uhmwpe.toml), so under
// the same load its stance pressures lie below the law as specified's (a softer foundation
// spreads the same force over more area) and closer to the deformable insert's, which is softer
// still on this coarse mesh; nothing is fitted, so these are checks of the plumbing, not of the
// law (docs/validation.md, contact_law_other_loads, judges the law on the reference mesh). A
// deformable config is refused with exit 2 and no summary.
#include <doctest/doctest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/cli_wear/cli_helpers.h"

using namespace kneesim::test;
namespace fs = std::filesystem;

TEST_CASE("kneesim check-contact: the shipped law against the deformable insert on another rig") {
  TempDir tmp;
  const fs::path out = tmp.path / "check";
  // the coarse mesh from the config file: its [deformable] keys replace the reference mesh's
  const fs::path config = tmp.path / "coarse.toml";
  spit(config, "[deformable]\nelement_size_mm = 3.0\nlayers = 3\n[solver]\nthreads = 2\n");
  const Result r = run_kneesim({"check-contact", config.string(), "--out", out.string(), "--set",
                                "rig.preset=\"iso\""},
                               tmp.path);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  for (const char* f : {"comparison.csv", "summary.json", "report.html", "calibration.png"}) {
    CHECK_MESSAGE(fs::exists(out / f), f);
  }
  CHECK(r.out.find("deformable insert") != std::string::npos);
  CHECK(r.out.find("rigid, law (library)") != std::string::npos);
  CHECK(r.err.find("not on the calibration's reference mesh") != std::string::npos);
  const auto s = nlohmann::json::parse(slurp(out / "summary.json"));
  CHECK(s["rig_preset"] == "iso");
  CHECK(s["contact_law"]["source"] == "library");
  CHECK(s["deformable_on_reference_mesh"] == false);
  CHECK(s["deformable_element_size_mm"] == 3.0);
  // the shipped UHMWPE law was fitted on the rigid runs' own surfaces (its provenance names no
  // finer ones), so the deformable insert runs on them too
  CHECK(s["deformable_sdf_spacing_mm"] == s["rigid_sdf_spacing_mm"]);
  CHECK(s["deformable_implant_edge_length_mm"] == s["rigid_implant_edge_length_mm"]);
  const double k_law = s["contact_law"]["foundation_modulus_MPa"];
  const double k_spec = s["specified_modulus_MPa"];
  CHECK(k_law < 0.5 * k_spec);
  const auto& f = s["stance_figures"];
  CHECK(f["rigid_law"]["peak_MPa"].get<double>() < f["rigid_as_specified"]["peak_MPa"].get<double>());
  CHECK(f["rigid_law"]["area_mm2"].get<double>() > f["rigid_as_specified"]["area_mm2"].get<double>());
  const auto& e = s["stance_0_60pct"];
  CHECK(e["rigid_law"]["peak_pressure_rms"].get<double>() <
        e["rigid_as_specified"]["peak_pressure_rms"].get<double>());
  CHECK(e["rigid_law"]["frames"].get<int>() > 40);  // stance frames in contact, of 61
  const double d = s["stance_difference"]["rigid_law"]["peak"];
  CHECK(d == doctest::Approx(f["rigid_law"]["peak_MPa"].get<double>() /
                                 f["deformable"]["peak_MPa"].get<double>() - 1.0));

  const Result refused = run_kneesim({"check-contact", "--out", (tmp.path / "c2").string(),
                                      "--set", "insert=\"deformable\""}, tmp.path);
  CHECK(refused.exit_code == 2);
  CHECK(refused.err.find("insert = \"deformable\" is not allowed") != std::string::npos);
  CHECK_FALSE(fs::exists(tmp.path / "c2" / "summary.json"));
}
