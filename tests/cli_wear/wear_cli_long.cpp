// The slower `kneesim` CLI checks of issue 3 (test_cli_wear_long, label "long"; ~20 s wall
// on the shared 2-core machine, ~6 s CPU):
//  - `kneesim compare` of three materials on the coarse implant for 500 000 cycles (two
//    updates): comparison.csv has the columns, one row per material, and the rankings
//    of the acceptance, which follow from the materials' data:
//    mean peak contact pressure rises with the insert modulus (685, 3500, 18 000 MPa):
//    UHMWPE < PEEK < CFR-PEEK (the materials study: 13.4 < 23.6 < 36.1 MPa); volumetric wear
//    ranks CFR-PEEK < UHMWPE < PEEK with the library's wear factors (k = 3.44e-11, 2.643e-10,
//    6.34e-10 mm^3/(N mm); the materials study: 15.6 < 124.0 < 300.9 mm^3);
//    and a material's wear.csv is the same as a lone `kneesim wear` run's (concurrency
//    changes nothing);
//  - `kneesim wear` killed before its first checkpoint, or after its last one (while the
//    plots are drawn): --resume writes the same wear.csv, final_depth.csv and kinematics.csv
//    as an uninterrupted run.
#include <doctest/doctest.h>

#include <cstring>
#include <map>

#include "tests/cli_wear/cli_helpers.h"

using namespace kneesim::test;

TEST_CASE("kneesim compare: comparison.csv with the columns and the rankings of issue 3") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path out = tmp.path / "cmp";
  const Result r = run_kneesim({"compare", "--materials", "uhmwpe,peek,cfr-peek", "--cycles",
                                "500000", "--update-every", "250000", "--set",
                                "implant.edge_length_mm=2", "--quiet", "--out", out.string()},
                               tmp.path);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  MESSAGE("kneesim compare, 3 materials x 500 000 cycles, coarse: " << r.seconds << " s wall");

  const std::string csv = slurp(out / "comparison.csv");
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split(line, ',');
  std::map<std::string, size_t> col;
  for (size_t i = 0; i < header.size(); ++i) col[header[i]] = i;
  for (const char* c : {"material", "volume_mm3", "mass_mg", "max_depth_mm",
                        "mean_peak_pressure_MPa", "ap_rom_mm", "ie_rom_mm"}) {
    REQUIRE_MESSAGE(col.count(c), "comparison.csv lacks the column " << c);
  }
  std::map<std::string, std::map<std::string, double>> row;  // material -> column -> value
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = split(line, ',');
    REQUIRE(cells.size() == header.size());
    for (const auto& [name, i] : col) {
      if (name != "material") row[cells[col["material"]]][name] = std::stod(cells[i]);
    }
  }
  REQUIRE(row.size() == 3);
  for (const char* m : {"uhmwpe", "peek", "cfr-peek"}) {
    REQUIRE_MESSAGE(row.count(m), "no row for " << m);
    MESSAGE(std::string(m) << ": volume " << row[m]["volume_mm3"] << " mm^3, mass " << row[m]["mass_mg"]
              << " mg, max depth " << row[m]["max_depth_mm"] << " mm, mean peak pressure "
              << row[m]["mean_peak_pressure_MPa"] << " MPa, AP " << row[m]["ap_rom_mm"]
              << " mm, IE " << row[m]["ie_rom_mm"] << " deg");
    CHECK(row[m]["volume_mm3"] > 0.0);
    CHECK(row[m]["max_depth_mm"] > 0.0);
    CHECK(row[m]["ap_rom_mm"] > 0.0);
    CHECK(row[m]["ie_rom_mm"] > 0.0);
  }
  CHECK(row["uhmwpe"]["mean_peak_pressure_MPa"] < row["peek"]["mean_peak_pressure_MPa"]);
  CHECK(row["peek"]["mean_peak_pressure_MPa"] < row["cfr-peek"]["mean_peak_pressure_MPa"]);
  CHECK(row["cfr-peek"]["volume_mm3"] < row["uhmwpe"]["volume_mm3"]);
  CHECK(row["uhmwpe"]["volume_mm3"] < row["peek"]["volume_mm3"]);
  // the markdown table and each material's own wear run are there too
  CHECK(fs::exists(out / "comparison.md"));
  for (const char* m : {"uhmwpe", "peek", "cfr-peek"}) CHECK(fs::exists(out / m / "wear.csv"));
  // running the materials concurrently changes nothing: PEEK's wear.csv equals that of a
  // lone `kneesim wear --material peek` with the same settings, byte for byte
  const fs::path alone = tmp.path / "peek_alone";
  const Result w =
      run_kneesim(wear_args(alone, {"--material", "peek"}, "250000", "500000"), tmp.path, "alone");
  REQUIRE(w.exit_code == 0);
  CHECK(same_bytes(slurp(alone / "wear.csv"), slurp(out / "peek" / "wear.csv")));
}

TEST_CASE("kneesim wear killed before its first checkpoint: --resume starts afresh, same wear.csv") {
  // reference: issue 3 ("a run killed at any moment resumes ... identical"); wear.csv first
  // appears after the settling cycle, before the first update's checkpoint
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path d1 = tmp.path / "D1", d3 = tmp.path / "D3";
  auto args = [](const fs::path& out, bool resume) {
    return wear_args(out, resume ? std::vector<std::string>{"--resume"} : std::vector<std::string>{});
  };
  const Result r1 = run_kneesim(args(d1, false), tmp.path, "d1");
  REQUIRE(r1.exit_code == 0);
  const Result k3 = kill_when_exists(args(d3, false), tmp.path, d3 / "wear.csv", "d3");
  REQUIRE(k3.signal == SIGKILL);
  CHECK_FALSE(fs::exists(d3 / "wear.checkpoint"));
  const Result r = run_kneesim(args(d3, true), tmp.path, "resume3");
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(same_bytes(slurp(d3 / "wear.csv"), slurp(d1 / "wear.csv")));
}

TEST_CASE("kneesim wear killed after its last checkpoint: --resume gives the same outputs") {
  // reference: issue 3 ("a run killed at any moment resumes ... identical"). The last
  // checkpoint (cycles done = the run's total) lives until the plots are drawn and
  // summary.json is written; a kill in that window leaves nothing to simulate on resume.
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path d1 = tmp.path / "D1", d4 = tmp.path / "D4";
  auto args = [](const fs::path& out, bool resume) {
    return wear_args(out, resume ? std::vector<std::string>{"--resume"} : std::vector<std::string>{},
                     "250000", "500000");
  };
  const Result r1 = run_kneesim(args(d1, false), tmp.path, "d1");
  REQUIRE(r1.exit_code == 0);
  // cycles done is the int64 after the 16-byte magic and the 8-byte identity
  const fs::path ckpt = d4 / "wear.checkpoint";
  auto final_checkpoint = [&ckpt] {
    std::ifstream in(ckpt, std::ios::binary);
    char b[32];
    if (!in.read(b, sizeof b)) return false;
    int64_t cycles = 0;
    std::memcpy(&cycles, b + 24, sizeof cycles);
    return cycles == 500000;
  };
  const Result k = kill_when(args(d4, false), tmp.path, final_checkpoint, "d4");
  REQUIRE_MESSAGE(k.signal == SIGKILL, "the run finished before it could be killed");
  CHECK_FALSE(fs::exists(d4 / "summary.json"));
  const Result r = run_kneesim(args(d4, true), tmp.path, "resume4");
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(same_bytes(slurp(d4 / "wear.csv"), slurp(d1 / "wear.csv")));
  CHECK(same_bytes(slurp(d4 / "final_depth.csv"), slurp(d1 / "final_depth.csv")));
  const std::string kin1 = slurp(d1 / "kinematics.csv"), kin4 = slurp(d4 / "kinematics.csv");
  INFO("kinematics.csv rows: uninterrupted " << count_lines(kin1) << ", resumed "
                                             << count_lines(kin4));
  CHECK(same_bytes(kin4, kin1));
}
