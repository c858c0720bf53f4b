// One clear sentence for the unclear cases of issue-28 item 5 (docs/robustness.md): each input
// below is refused with exit 2 (or, for a user material missing properties, runs and says
// which defaults it took) naming the file and line, key or flag, the value and the allowed
// range, never a raw library text ("Could not convert", assimp's words, "rows , ..."); a decimal
// comma or another separator in a measured table is named; every numeric option of every
// command (item 4) refuses a non-number and a value out of range with its range.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/cli_wear/cli_helpers.h"

namespace fs = std::filesystem;
using namespace kneesim::test;

namespace {

// a binary STL of one tetrahedron (4 triangles), optionally with a wrong count or cut off
std::string tetra_stl(std::uint32_t count_written, size_t cut = 0) {
  std::string s(80, '\0');
  s.append(reinterpret_cast<const char*>(&count_written), 4);
  const float v[4][3] = {{0, 0, 0}, {0.05f, 0, 0}, {0, 0.05f, 0}, {0, 0, 0.05f}};
  const int tris[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& t : tris) {
    s.append(12, '\0');
    for (int k : t) s.append(reinterpret_cast<const char*>(v[k]), 12);
    s.append(2, '\0');
  }
  if (cut > 0) s.resize(s.size() - cut);
  return s;
}

std::string mesh_config(const std::string& femur, const std::string& insert) {
  return "[implant]\nkind = \"mesh\"\n[implant.mesh]\nfemur = \"" + femur + "\"\ninsert = \"" +
         insert + "\"\nunits = \"m\"\n";
}

Result check_implant(const TempDir& tmp, const std::string& femur, const std::string& insert,
                     const std::string& tag) {
  spit(tmp.path / (tag + ".toml"), mesh_config(femur, insert));
  return run_kneesim({"implant", "check", (tmp.path / (tag + ".toml")).string(), "--out",
                      (tmp.path / ("o_" + tag)).string(), "--no-plots"},
                     tmp.path, tag);
}

void refused(const Result& r, const std::vector<std::string>& parts) {
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 2);
  CHECK(count_lines(r.err) == 1);
  for (const auto& p : parts) CHECK(r.err.find(p) != std::string::npos);
  CHECK(r.err.find("assimp") == std::string::npos);
  CHECK(r.err.find("Could not convert") == std::string::npos);
}

}  // namespace

TEST_CASE("mesh files that are not what their name says") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  spit(tmp.path / "good.stl", tetra_stl(4));
  spit(tmp.path / "cut.stl", tetra_stl(4, 30));
  spit(tmp.path / "count.stl", tetra_stl(7));
  spit(tmp.path / "image.stl", std::string("\x89PNG\r\n\x1a\n", 8) + std::string(200, 'x'));
  fs::create_directories(tmp.path / "folder.stl");
  spit(tmp.path / "face.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n# a comment\nf 1 2 3\nf 1 2 9\n");
  const std::string good = (tmp.path / "good.stl").string();
  refused(check_implant(tmp, (tmp.path / "cut.stl").string(), good, "cut"),
          {"cut.stl: is not a complete binary STL: its header counts 4 triangles, which take 284 "
           "bytes, but the file has 254 bytes"});
  refused(check_implant(tmp, (tmp.path / "count.stl").string(), good, "count"),
          {"count.stl: is not a complete binary STL: its header counts 7 triangles"});
  refused(check_implant(tmp, (tmp.path / "image.stl").string(), good, "image"),
          {"image.stl: is a PNG image, not a mesh"});
  refused(check_implant(tmp, (tmp.path / "folder.stl").string(), good, "folder"),
          {"folder.stl: is a folder, not a mesh file"});
  refused(check_implant(tmp, (tmp.path / "face.obj").string(), good, "face"),
          {"face.obj: line 6: face index 9 names no vertex: 3 vertices are defined above it "
           "(allowed: 1 to 3"});
}

TEST_CASE("whole-number options say the range; --convergence names itself") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const std::string out = (tmp.path / "w").string();
  refused(run_kneesim({"wear", "--cycles", "1e3", "--out", out}, tmp.path, "c"),
          {"--cycles: value '1e3' is not a whole number (write 1000); allowed: a whole number 1 "
           "to 1000000000"});
  refused(run_kneesim({"wear", "--schedule", "100000,abc", "--out", out}, tmp.path, "s"),
          {"--schedule: value 'abc' is not a whole number; allowed: a whole number 1 to "
           "1000000000"});
  refused(run_kneesim({"wear", "--convergence", "0", "--out", out}, tmp.path, "v0"),
          {"--convergence: value '0' is not in the allowed range 1 to 1000000000"});
  const Result one = run_kneesim({"wear", "--convergence", "1", "--out", out}, tmp.path, "v1");
  refused(one, {"--convergence = 1 needs more than 10000 geometry updates", "e.g. --convergence"});
  CHECK(one.err.find("--update-every") == std::string::npos);
}

TEST_CASE("tables, gait file and user materials") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  // a spreadsheet that writes ';' between cells (whole numbers: the header has no column)
  spit(tmp.path / "semi.csv", "load_N;cycles;volume_mm3\n225;0;0\n225;50000;1\n");
  refused(run_kneesim({"diagnose", "bor", "--measured", (tmp.path / "semi.csv").string(), "--out",
                       (tmp.path / "d1").string()}, tmp.path, "semi"),
          {"semi.csv: row 1 (header) has no column 'load_N'", "separated by ';', not ','"});
  // ... and with decimal commas in a row: the row, the separator and the number
  spit(tmp.path / "semidec.csv", "load_N;cycles;volume_mm3\n225;0;0\n225;50000;0,5\n");
  refused(run_kneesim({"diagnose", "bor", "--measured", (tmp.path / "semidec.csv").string(),
                       "--out", (tmp.path / "d3").string()}, tmp.path, "semidec"),
          {"semidec.csv: row 3 has 2 fields but the header has 1 (the file looks separated by ';' "
           "with decimal commas ('0,5')"});
  // a decimal comma in a comma-separated row: the row and the likely decimal comma
  spit(tmp.path / "dec.csv", "load_N,cycles,volume_mm3\n225,0,0\n225,50000,0,5\n");
  refused(run_kneesim({"diagnose", "bor", "--measured", (tmp.path / "dec.csv").string(), "--out",
                       (tmp.path / "d4").string()}, tmp.path, "dec"),
          {"dec.csv: row 3 has 4 fields but the header has 3 (likely a decimal comma"});
  // measured kinematics of `run --measured`: a ';' header and a decimal comma in a row
  spit(tmp.path / "kin_semi.csv", "gait_pct;ap_mm;ie_deg\n0;0;0\n50;1,5;2\n");
  refused(run_kneesim({"run", "--measured", (tmp.path / "kin_semi.csv").string(), "--out",
                       (tmp.path / "k1").string(), "--quiet"}, tmp.path, "kin_semi"),
          {"kin_semi.csv: line 1 (header) 'gait_pct;ap_mm;ie_deg' is separated by ';', not ','"});
  spit(tmp.path / "kin_dec.csv", "gait_pct,ap_mm,ie_deg\n0,0,0\n50,1,5,2\n");
  refused(run_kneesim({"run", "--measured", (tmp.path / "kin_dec.csv").string(), "--out",
                       (tmp.path / "k2").string(), "--quiet"}, tmp.path, "kin_dec"),
          {"kin_dec.csv: line 3 has 4 cells but the header has 3 columns (likely a decimal comma"});
  // every volume at cycle 0: nothing to calibrate
  spit(tmp.path / "zero.csv", "load_N,cycles,volume_mm3\n225,0,0\n225,0,0.1\n130,0,0\n");
  const Result z = run_kneesim({"diagnose", "bor", "--measured", (tmp.path / "zero.csv").string(),
                                "--out", (tmp.path / "d2").string()}, tmp.path, "zero");
  refused(z, {"zero.csv: column cycles at the calibration load 225 N: no volume_mm3 row has "
              "cycles > 0"});
  CHECK(z.err.find("rows ,") == std::string::npos);
  // a gait file that is not there: the key is named
  spit(tmp.path / "gait.toml", "[gait]\nfile = \"no_such_gait.csv\"\n");
  refused(run_kneesim({"run", (tmp.path / "gait.toml").string(), "--out",
                       (tmp.path / "g").string(), "--quiet"}, tmp.path, "gait"),
          {"gait.toml: gait.file = \"no_such_gait.csv\": no file '"});
  // a user material with only a modulus: it runs, saying which defaults it took
  spit(tmp.path / "mat.toml", "[material]\nname = \"soft\"\n[materials.soft]\n"
                              "elastic_modulus_MPa = 500.0\n");
  const Result m = run_kneesim({"run", (tmp.path / "mat.toml").string(), "--cycles", "1", "--set",
                                "implant.edge_length_mm=3", "--no-calibrate", "--out",
                                (tmp.path / "m").string(),
                                "--quiet", "--no-plots", "--no-report"},
                               tmp.path, "mat");
  INFO(m.err);
  CHECK(m.exit_code == 0);
  CHECK(m.err.find("material 'soft' does not set every property; it takes the built-in "
                   "defaults (UHMWPE against CoCr) poisson = 0.47, friction = 0.07") !=
        std::string::npos);
  CHECK(m.err.find("wear_factor_mm3_per_Nmm = 2.643e-10") != std::string::npos);
}

TEST_CASE("every numeric option refuses a non-number or a value out of range, naming both") {
  // reference: the ranges in each command's --help and docs/robustness.md; every refusal comes
  // before any work (none of these runs a simulation)
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  spit(tmp.path / "bor.csv", "load_N,cycles,volume_mm3\n225,0,0\n225,50000,1\n225,100000,2\n");
  const std::string bor_csv = (tmp.path / "bor.csv").string();
  const std::string out = (tmp.path / "o").string();
  struct Case {
    std::vector<std::string> args;
    std::string says;
  };
  const std::vector<Case> cases = {
      {{"bor", "--update-every", "-1"}, "--update-every: value '-1' is not in the allowed range 1 to 1000000000"},
      {{"bor", "--fe-element-mm", "abc"}, "--fe-element-mm: value 'abc' is not a finite number; allowed: [0.02, 1] mm"},
      {{"bor", "--fe-element-mm", "5"}, "--fe-element-mm = 5 mm is outside the allowed range [0.02, 1] mm"},
      {{"bor", "--fe-max-steps", "nan"}, "--fe-max-steps: value 'nan' is not a whole number; allowed: a whole number 100 to 100000000"},
      {{"bor", "--threads", "1.5"}, "--threads: value '1.5' is not a whole number; allowed: a whole number 1 to 64"},
      {{"bor", "--load-N", "abc"}, "--load-N: value 'abc' is not a finite number; allowed: (0, 10000] N"},
      {{"bor", "--ring-diameter-mm", "-1"}, "--ring-diameter-mm = -1 is outside the allowed range (0, 2000] mm"},
      {{"bor", "--friction", "abc"}, "--friction: value 'abc' is not a finite number; allowed: [0, 2]"},
      {{"bor", "--poisson", "0.5"}, "--poisson = 0.5 is outside the allowed range (-1, 0.4999]"},
      {{"bor", "--ring-width-mm", "20"}, "--ring-width-mm = 20 exceeds --block-width-mm = 12"},
      {{"diagnose", "bor", "--measured", bor_csv, "--bootstrap", "nan"}, "--bootstrap: value 'nan' is not a whole number; allowed: a whole number 0 to 100000"},
      {{"diagnose", "bor", "--measured", bor_csv, "--seed", "-1"}, "--seed: value '-1' is not in the allowed range 0 to 9007199254740991"},
      {{"diagnose", "bor", "--measured", bor_csv, "--ic-threshold", "x"}, "--ic-threshold: value 'x' is not a finite number; allowed: [0, 1000]"},
      {{"diagnose", "bor", "--measured", bor_csv, "--block-height-mm", "0"}, "--block-height-mm = 0 is outside the allowed range (0, 1000] mm"},
      {{"diagnose", "forces", "--grid-points", "x"}, "--grid-points: value 'x' is not a whole number; allowed: a whole number 4 to 41"},
      {{"diagnose", "kinematics", "--measured", bor_csv, "--config", bor_csv, "--stance-end-pct", "abc"}, "--stance-end-pct: value 'abc' is not a finite number; allowed: (0, 100) %"},
      {{"diagnose", "kinematics", "--measured", bor_csv, "--config", bor_csv, "--threads", "1.5"}, "--threads: value '1.5' is not a whole number; allowed: a whole number 1 to 256"},
      {{"study", "--seed", "-1"}, "--seed: value '-1' is not in the allowed range 0 to 9007199254740991"},
      {{"study", "--trials", "1e3"}, "--trials: value '1e3' is not a whole number (write 1000); allowed: a whole number 2 to 10000000"},
      {{"study", "--wear", "--wear-cycles", "abc"}, "--wear-cycles: value 'abc' is not a whole number; allowed: a whole number 1 to 1000000000"},
      {{"study", "--wear", "--wear-updates", "0"}, "--wear-updates: value '0' is not in the allowed range 1 to 1000"},
      {{"run", "--cycles", "1e3"}, "--cycles: value '1e3' is not a whole number (write 1000); allowed: a whole number 1 to 1000000"},
      {{"run", "--export-fe-pcts", "abc"}, "--export-fe-pcts: value 'abc' is not a number in the allowed range 0 to 99.999"},
      {{"compare", "--jobs", "1.5"}, "--jobs: value '1.5' is not a whole number; allowed: a whole number 1 to 1024"},
      {{"particles", "--max-iterations", "2.5"}, "--max-iterations: value '2.5' is not a whole number; allowed: a whole number 1 to 1000000"},
  };
  int i = 0;
  for (const Case& c : cases) {
    std::vector<std::string> args = c.args;
    args.push_back("--out");
    args.push_back(out);
    args.back() += std::to_string(i);
    CAPTURE(args[0] + " " + args[1] + " " + args[2]);
    std::string tag = "n";
    tag += std::to_string(i++);
    refused(run_kneesim(args, tmp.path, tag), {c.says});
  }
}
