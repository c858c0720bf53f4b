// One clear sentence for the unclear cases of issue-28 item 5 (docs/robustness.md): each input
// below is refused with exit 2 (or, for a user material missing properties, runs and says
// which defaults it took) naming the file and line, key or flag, the value and the allowed
// range, never a raw library text ("Could not convert", assimp's words, "rows , ...").
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
  // a spreadsheet that writes ';' between cells (whole numbers here: a decimal comma in a row
  // is reported as that row's field count, without the separator)
  spit(tmp.path / "semi.csv", "load_N;cycles;volume_mm3\n225;0;0\n225;50000;1\n");
  refused(run_kneesim({"diagnose", "bor", "--measured", (tmp.path / "semi.csv").string(), "--out",
                       (tmp.path / "d1").string()}, tmp.path, "semi"),
          {"semi.csv: row 1 (header) has no column 'load_N'", "separated by ';', not ','"});
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
                                "implant.edge_length_mm=3", "--out", (tmp.path / "m").string(),
                                "--quiet", "--no-plots", "--no-report"},
                               tmp.path, "mat");
  INFO(m.err);
  CHECK(m.exit_code == 0);
  CHECK(m.err.find("material 'soft' does not set every property; it takes the built-in "
                   "defaults (UHMWPE against CoCr) poisson = 0.47, friction = 0.07") !=
        std::string::npos);
  CHECK(m.err.find("wear_factor_mm3_per_Nmm = 2.643e-10") != std::string::npos);
}
