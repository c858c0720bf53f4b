// `kneesim study` end to end on a coarse knee model (2 mm insert edge, Pal 2008's 13 variables).
// References: byte equality of trials.csv between a serial run, a 2-thread run, a killed and
// resumed run and a 2-rank MPI run (design.md "Determinism"); the error contract (exit 2, one
// sentence naming the input) for bad input before any trial runs.
#include <doctest/doctest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>

#include "tests/cli_wear/cli_helpers.h"

using namespace kneesim::test;

namespace {

std::vector<std::string> study_args(const fs::path& out, const std::string& threads,
                                    std::vector<std::string> extra = {}) {
  std::vector<std::string> a = {"study", "--method", "lhs", "--trials", "6", "--seed", "3",
                                "--set", "implant.edge_length_mm=2", "--threads", threads,
                                "--quiet", "--out", out.string()};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

}  // namespace

TEST_CASE("kneesim study: serial, 2 threads, and killed + resumed give the same trials.csv") {
  TempDir tmp;
  const fs::path serial = tmp.path / "serial", two = tmp.path / "two", killed = tmp.path / "killed";
  const Result a = run_kneesim(study_args(serial, "1"), tmp.path, "serial");
  REQUIRE_MESSAGE(a.exit_code == 0, a.err);
  const Result b = run_kneesim(study_args(two, "2"), tmp.path, "two");
  REQUIRE_MESSAGE(b.exit_code == 0, b.err);
  const std::string trials = slurp(serial / "trials.csv");
  CHECK(count_lines(trials) == 7);
  CHECK(same_bytes(trials, slurp(two / "trials.csv")));
  for (const char* f : {"envelopes.csv", "sensitivity.csv", "summary.json"})
    CHECK(fs::exists(serial / f));
  const auto s = nlohmann::json::parse(slurp(serial / "summary.json"));
  CHECK(s["trials_done"].get<long>() + s["trials_failed"].get<long>() == 6);
  CHECK(s["variables"].size() == 13);

  // killed once two trials are journaled (header + 2 lines), then resumed
  const fs::path journal = killed / "trials.journal.0";
  const Result k = kill_when(study_args(killed, "1"), tmp.path,
                             [&] { return fs::exists(journal) && count_lines(slurp(journal)) >= 3; },
                             "killed");
  CHECK(k.signal == SIGKILL);
  CHECK_FALSE(fs::exists(killed / "trials.csv"));
  const Result r = run_kneesim(study_args(killed, "2", {"--resume"}), tmp.path, "resumed");
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(same_bytes(trials, slurp(killed / "trials.csv")));
  const auto rs = nlohmann::json::parse(slurp(killed / "summary.json"));
  CHECK(rs["trials_resumed"].get<long>() >= 2);
  CHECK(rs["trials_resumed"].get<long>() + rs["trials_computed"].get<long>() == 6);
  CHECK_FALSE(fs::exists(journal));

  // 2 MPI ranks on loopback, one thread each
  const char* mpiexec = std::getenv("KNEESIM_MPIEXEC");
  if (mpiexec && *mpiexec) {
    const fs::path ranks = tmp.path / "ranks";
    std::string cmd = std::string(mpiexec) + " --allow-run-as-root --oversubscribe --bind-to "
                      "none -np 2 " + find_kneesim().string();
    for (const auto& x : study_args(ranks, "1")) cmd += " '" + x + "'";
    const int rc = std::system((cmd + " > " + (tmp.path / "mpi.log").string() + " 2>&1").c_str());
    REQUIRE_MESSAGE(rc == 0, slurp(tmp.path / "mpi.log"));
    CHECK(same_bytes(trials, slurp(ranks / "trials.csv")));
    const auto ms = nlohmann::json::parse(slurp(ranks / "summary.json"));
    CHECK(ms["trials_computed"].get<long>() == 6);

    // ranks launched with different configs: refused before any trial
    const fs::path bad = tmp.path / "disagree";
    std::string cmd2 = std::string(mpiexec) + " --allow-run-as-root --oversubscribe --bind-to "
                       "none -np 2 sh -c '" + find_kneesim().string() +
                       " study --trials 4 --set implant.edge_length_mm=2 --set "
                       "rig.restraint.gap_mm=3.$OMPI_COMM_WORLD_RANK --quiet --out " +
                       bad.string() + "'";
    const int rc2 = std::system((cmd2 + " > " + (tmp.path / "mpi2.log").string() + " 2>&1").c_str());
    CHECK(rc2 != 0);
    CHECK(slurp(tmp.path / "mpi2.log").find("disagree") != std::string::npos);
    CHECK_FALSE(fs::exists(bad / "trials.csv"));
  } else {
    MESSAGE("no MPI launcher in this build: the 2-rank check is skipped");
  }
}

TEST_CASE("kneesim study: bad input is refused with exit 2 before any trial runs") {
  TempDir tmp;
  struct Case {
    std::vector<std::string> extra;
    const char* says;
  };
  for (const Case& c : {Case{{"--var", "rig.no_such=normal(1, 0.1)"}, "not a number key"},
                        Case{{"--var", "contact.friction=normal(nominal, 0)"}, "positive"},
                        Case{{"--var", "rig.restraint.k_anterior_N_per_mm=normal(4.75, 5)"},
                             "--allow-truncation"}}) {
    const fs::path out = tmp.path / "bad";
    const Result r = run_kneesim(study_args(out, "1", c.extra), tmp.path, "bad");
    CAPTURE(r.err);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(c.says) != std::string::npos);
    CHECK_FALSE(fs::exists(out / "trials.csv"));
    CHECK_FALSE(fs::exists(out / "trials.journal.0"));
  }
  const Result m = run_kneesim({"study", "--method", "sobol", "--out", (tmp.path / "m").string()},
                               tmp.path, "method");
  CHECK(m.exit_code == 2);
  CHECK(m.err.find("--method") != std::string::npos);
  // allowed truncation runs and is reported
  const fs::path out = tmp.path / "truncated";
  const Result r = run_kneesim({"study", "--trials", "2", "--var",
                                "rig.restraint.k_anterior_N_per_mm=normal(4.75, 5)",
                                "--allow-truncation", "--set", "implant.edge_length_mm=2",
                                "--out", out.string()},
                               tmp.path, "truncated");
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(r.err.find("truncated") != std::string::npos);
  const auto s = nlohmann::json::parse(slurp(out / "summary.json"));
  CHECK(s["variables"]["rig.restraint.k_anterior_N_per_mm"]["truncated_mass"].get<double>() > 0.1);
}
