// `kneesim compare` bad input (issue 3): an unknown material stops the command before any
// simulation, with one line on stderr and exit 2 (the rankings run in test_cli_wear_long).
#include <doctest/doctest.h>

#include "tests/cli_wear/cli_helpers.h"

using namespace kneesim::test;

TEST_CASE("kneesim compare: an unknown material stops it before any simulation") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path out = tmp.path / "cmp";
  const Result r = run_kneesim({"compare", "--materials", "uhmwpe,unobtainium", "--cycles",
                                "500000", "--update-every", "250000", "--quiet", "--out",
                                out.string()},
                               tmp.path);
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK(count_lines(r.err) == 1);
  CHECK(r.err.find("unobtainium") != std::string::npos);
  CHECK_FALSE(fs::exists(out / "comparison.csv"));
  CHECK_FALSE(fs::exists(out / "uhmwpe" / "wear.csv"));
}
