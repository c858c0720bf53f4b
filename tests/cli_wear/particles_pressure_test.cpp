// `kneesim particles` for a knee pair takes its contact pressure from a kneesim contact run of
// the same insert material (issue 14 item 5), not from a paper: the Hertz peak it sizes the
// cylinder to (summary.json contact_pressure_MPa) is the mean peak pressure `kneesim run
// --set material.name=<material>` reports (the same settled cycle of the rigid insert), to
// 1e-9 relative; one wear-loop iteration keeps the test short.
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "tests/cli_wear/cli_helpers.h"

using namespace kneesim::test;

TEST_CASE("kneesim particles: a knee pair's contact pressure is kneesim's own") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path run_dir = tmp.path / "run", part_dir = tmp.path / "part";
  const Result run = run_kneesim(
      {"run", "--quiet", "--set", "material.name=cfr-peek", "--out", run_dir.string()}, tmp.path,
      "run");
  INFO("run stderr: " << run.err);
  REQUIRE(run.exit_code == 0);
  const Result part = run_kneesim({"particles", "--pair", "cfrpeek-cocr", "--max-iterations", "1",
                                   "--no-plots", "--out", part_dir.string()},
                                  tmp.path, "part");
  INFO("particles stderr: " << part.err);
  REQUIRE(part.exit_code == 0);
  const auto r = nlohmann::json::parse(slurp(run_dir / "summary.json"));
  const auto p = nlohmann::json::parse(slurp(part_dir / "summary.json"));
  MESSAGE("CFR-PEEK: kneesim run mean peak pressure " << r["mean_peak_pressure_MPa"].get<double>()
          << " MPa; particles contact pressure " << p["contact_pressure_MPa"].get<double>()
          << " MPa (" << p["contact_pressure_source"].get<std::string>() << ")");
  CHECK(p["contact_pressure_MPa"].get<double>() ==
        doctest::Approx(r["mean_peak_pressure_MPa"].get<double>()).epsilon(1e-9));
  CHECK(p["contact_pressure_source"].get<std::string>().find("kneesim run") != std::string::npos);
}
