// `kneesim compare` bad input (issue 3): an unknown material stops the command before any
// simulation, with one line on stderr and exit 2 (the rankings run in test_cli_wear_long).
// A comparison SIGKILLed while its second material runs and continued with --resume: the
// finished material is taken from its summary.json (not simulated again), the interrupted one
// continues from its checkpoint, and every material's wear.csv is byte-identical to the
// uninterrupted comparison's (reference: the checkpoint invariant of issue 3, resumed equals
// uninterrupted bit for bit, carried through compare).
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

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

TEST_CASE("kneesim compare killed mid-way: --resume finishes it with the uninterrupted results") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  // one material at a time, so that uhmwpe has finished when peek's first checkpoint appears
  auto args = [](const fs::path& out, std::vector<std::string> extra = {}) {
    std::vector<std::string> a = {"compare", "--materials", "uhmwpe,peek", "--cycles", "1000000",
                                  "--update-every", "250000", "--jobs", "1", "--quiet", "--no-break-even",
                                  "--set", "implant.edge_length_mm=2", "--out", out.string()};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  const fs::path ref = tmp.path / "ref", cut = tmp.path / "cut";
  const Result r1 = run_kneesim(args(ref), tmp.path, "ref");
  INFO("stderr: " << r1.err);
  REQUIRE(r1.exit_code == 0);

  const Result k = kill_when_exists(args(cut), tmp.path, cut / "peek" / "wear.checkpoint", "cut");
  REQUIRE_MESSAGE(k.signal == SIGKILL, "the comparison finished before it could be killed");
  REQUIRE(fs::exists(cut / "uhmwpe" / "summary.json"));
  CHECK_FALSE(fs::exists(cut / "comparison.csv"));
  const std::string uhmwpe_summary = slurp(cut / "uhmwpe" / "summary.json");

  const Result r2 = run_kneesim(args(cut, {"--resume"}), tmp.path, "resume");
  INFO("stderr: " << r2.err);
  REQUIRE(r2.exit_code == 0);
  for (const char* m : {"uhmwpe", "peek"}) {
    CAPTURE(m);
    CHECK(same_bytes(slurp(cut / m / "wear.csv"), slurp(ref / m / "wear.csv")));
    CHECK_FALSE(fs::exists(cut / m / "wear.checkpoint"));
  }
  // the finished material was not simulated again: its summary (run time included) is unchanged
  CHECK(same_bytes(slurp(cut / "uhmwpe" / "summary.json"), uhmwpe_summary));
  const auto peek = nlohmann::json::parse(slurp(cut / "peek" / "summary.json"));
  CHECK(peek.contains("resumed_after_update"));
  CHECK(fs::exists(cut / "comparison.csv"));
  CHECK(fs::exists(cut / "compare_wear.png"));

  // a finished run under other settings is not taken for this one: --resume with another
  // friction simulates again and gives other volumes; with --no-plots, the previous plots are
  // gone and none is drawn, and the tables are written
  const Result r3 = run_kneesim(
      args(cut, {"--resume", "--set", "contact.friction=0.02", "--no-plots"}), tmp.path, "other");
  INFO("stderr: " << r3.err);
  REQUIRE(r3.exit_code == 0);
  CHECK_FALSE(same_bytes(slurp(cut / "uhmwpe" / "wear.csv"), slurp(ref / "uhmwpe" / "wear.csv")));
  CHECK(fs::exists(cut / "comparison.csv"));
  CHECK_FALSE(fs::exists(cut / "compare_wear.png"));
  CHECK_FALSE(fs::exists(cut / "uhmwpe" / "wear.png"));
}
