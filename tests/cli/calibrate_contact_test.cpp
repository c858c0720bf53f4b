// `kneesim calibrate-contact` end to end on a coarse case (3 mm elements, 3 layers, the
// reference load case's 1 s cycle): it writes the law file, the comparison and the summary;
// the calibrated law reduces the stance peak-pressure error on the fitting window (it
// minimizes it there, so it cannot do worse than the specified law unless the specified
// modulus lies outside the search range); a config naming the law file runs, and one of
// another material is refused (exit 2, one sentence naming the file), as is a --set of a key
// the reference load case would not use. The acceptance figures come from the full run in
// docs/deformable.md.
#include <doctest/doctest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/cli_wear/cli_helpers.h"

using namespace kneesim::test;
namespace fs = std::filesystem;

TEST_CASE("kneesim calibrate-contact writes a law file that a config can name") {
  TempDir tmp;
  const fs::path out = tmp.path / "cal";
  const std::vector<std::string> coarse = {"--set", "deformable.layers=3", "--set",
                                           "solver.threads=2"};
  std::vector<std::string> args = {"calibrate-contact", "--material", "uhmwpe", "--out",
                                   out.string(), "--element-mm", "3"};
  args.insert(args.end(), coarse.begin(), coarse.end());
  const Result r = run_kneesim(args, tmp.path);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  for (const char* f : {"contact_law.toml", "comparison.csv", "summary.json"}) {
    CHECK_MESSAGE(fs::exists(out / f), f);
  }
  const auto s = nlohmann::json::parse(slurp(out / "summary.json"));
  const double spec = s["fit_window_0_30pct"]["rigid_as_specified"]["peak_pressure_rms"];
  const double cal = s["fit_window_0_30pct"]["rigid_calibrated"]["peak_pressure_rms"];
  CHECK(s["calibrated_modulus_MPa"].get<double>() < s["specified_modulus_MPa"].get<double>());
  CHECK(cal < spec);

  const std::string law = (out / "contact_law.toml").string();
  std::vector<std::string> run = {"run", "--quiet", "--cycles", "1", "--out",
                                  (tmp.path / "run").string(), "--set",
                                  "contact.law_file=\"" + law + "\""};
  run.insert(run.end(), coarse.begin(), coarse.end());
  const Result good = run_kneesim(run, tmp.path);
  INFO("stderr: " << good.err);
  CHECK(good.exit_code == 0);
  const auto summary = nlohmann::json::parse(slurp(tmp.path / "run" / "summary.json"));
  CHECK(summary["contact_foundation_modulus_MPa"].get<double>() ==
        doctest::Approx(s["calibrated_modulus_MPa"].get<double>()));

  run.push_back("--set");
  run.push_back("material.name=\"peek\"");
  const Result other = run_kneesim(run, tmp.path);
  CHECK(other.exit_code == 2);
  CHECK(other.err.find(law) != std::string::npos);
  CHECK(other.err.find("calibrated for material \"uhmwpe\"") != std::string::npos);

  // a key the calibration's reference load case would not use is refused, not dropped
  for (const char* set : {"rig.preset=\"iso\"", "gait.period_s=0.2", "implant.edge_length_mm=2"}) {
    CAPTURE(set);
    const Result refused = run_kneesim({"calibrate-contact", "--out", (tmp.path / "cal3").string(),
                                        "--set", set}, tmp.path);
    CHECK(refused.exit_code == 2);
    CHECK(refused.err.find(std::string("--set ") + set + ": the calibration runs on its reference "
                           "load case") != std::string::npos);
    CHECK_FALSE(fs::exists(tmp.path / "cal3" / "summary.json"));
  }
}

// the deformable reference on finer surfaces than the rigid runs' (--reference-edge-mm): the
// provenance records them, and a --deformable-from run on other surfaces is refused by name
TEST_CASE("kneesim calibrate-contact: the reference's surfaces are recorded and checked") {
  TempDir tmp;
  const std::vector<std::string> mesh = {
      "--set", "deformable.element_size_mm=3", "--set", "deformable.layers=3",
      "--set", "deformable.grading=0.15",      "--set", "deformable.refine=\"contact\"",
      "--set", "solver.threads=2"};
  std::vector<std::string> run = {"run", "--quiet", "--no-plots", "--cycles", "1",
                                  "--set", "insert=\"deformable\"", "--set",
                                  "implant.edge_length_mm=1.5", "--out",
                                  (tmp.path / "fine").string()};
  run.insert(run.end(), mesh.begin(), mesh.end());
  const Result made = run_kneesim(run, tmp.path);
  INFO("stderr: " << made.err);
  REQUIRE(made.exit_code == 0);
  const auto made_summary = nlohmann::json::parse(slurp(tmp.path / "fine" / "summary.json"));
  CHECK(made_summary["implant_edge_length_mm"].get<double>() == 1.5);
  CHECK(made_summary["sdf_spacing_mm"].get<double>() == 0.4);

  std::vector<std::string> cal = {"calibrate-contact", "--material", "uhmwpe", "--exponent", "1",
                                  "--no-plots", "--quiet", "--element-mm", "3",
                                  "--deformable-from", (tmp.path / "fine").string()};
  cal.insert(cal.end(), mesh.begin(), mesh.end());
  std::vector<std::string> good = cal;
  good.insert(good.end(), {"--reference-edge-mm", "1.5", "--out", (tmp.path / "cal").string()});
  const Result ok = run_kneesim(good, tmp.path);
  INFO("stderr: " << ok.err);
  REQUIRE(ok.exit_code == 0);
  const auto s = nlohmann::json::parse(slurp(tmp.path / "cal" / "summary.json"));
  CHECK(s["reference_edge_length_mm"].get<double>() == 1.5);
  CHECK(s["deformable_mesh"].get<std::string>().find(
            "surfaces 1.5 mm facets, distance field 0.4 mm (the rigid runs: 1 mm, 0.4 mm)") !=
        std::string::npos);
  const std::string law = slurp(tmp.path / "cal" / "contact_law.toml");
  CHECK(law.find("reference_edge_length_mm = 1.5") != std::string::npos);
  CHECK(law.find("--reference-edge-mm 1.5") != std::string::npos);

  // the same run named without its surfaces: the rigid runs' 1 mm facets are not what it used
  std::vector<std::string> bad = cal;
  bad.insert(bad.end(), {"--out", (tmp.path / "cal2").string()});
  const Result refused = run_kneesim(bad, tmp.path);
  CHECK(refused.exit_code == 2);
  CHECK(refused.err.find("implant_edge_length_mm = 1.5, the calibration needs 1.0") !=
        std::string::npos);
}
