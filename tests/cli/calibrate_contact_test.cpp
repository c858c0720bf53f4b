// `kneesim calibrate-contact` end to end on a coarse, short case (3 mm elements, 3 layers,
// one 0.2 s cycle): it writes the law file, the comparison and the summary; the calibrated law
// reduces the stance peak-pressure error on the fitting window (it minimizes it there, so it
// cannot do worse than the specified law unless the specified modulus lies outside the search
// range); a config naming the law file runs, and one of another material is refused (exit 2,
// one sentence naming the file). The acceptance figures come from the full run in
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
  const std::vector<std::string> coarse = {
      "--set", "deformable.layers=3", "--set", "implant.edge_length_mm=2",
      "--set", "gait.period_s=0.2",   "--set", "solver.threads=2"};
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
}
