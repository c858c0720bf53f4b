// Mesh sanity end to end (issue 15): a NaN or a 1e30 vertex in the insert or the femoral mesh,
// a millimetre mesh declared as metres and the reverse were accepted (a "complete" run with
// elements silently dropped and wear of nan or 1.4e28 mm^3, or a raw std::bad_alloc). Through
// the built `kneesim run` and `kneesim wear`: exit 2, one sentence naming the file and what is
// wrong, and no result that looks complete (no summary.json, kinematics.csv or wear.csv). The
// meshes are the built-in implant's, written as ASCII STL; the same files unbroken run (the
// control that the set-up itself is sound).
#include <doctest/doctest.h>

#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "models/generic_tkr.h"
#include "tests/cli_wear/cli_helpers.h"

using namespace kneesim;
using namespace kneesim::test;

namespace {

// ASCII STL of `m` with its coordinates times `scale`; the first vertex's x replaced by `bad`
// when given (the text as written, e.g. "nan" or "1e30")
void write_stl(const fs::path& file, const models::TriMesh& m, double scale,
               const std::string& bad = "") {
  std::string s = "solid kneesim_test\n";
  char buf[160];
  bool first = true;
  for (const auto& t : m.triangles) {
    s += " facet normal 0 0 0\n  outer loop\n";
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = m.vertices[t[k]] * scale;
      if (first && !bad.empty()) {
        std::snprintf(buf, sizeof buf, "   vertex %s %.9g %.9g\n", bad.c_str(), p.y(), p.z());
      } else {
        std::snprintf(buf, sizeof buf, "   vertex %.9g %.9g %.9g\n", p.x(), p.y(), p.z());
      }
      first = false;
      s += buf;
    }
    s += "  endloop\n endfacet\n";
  }
  s += "endsolid kneesim_test\n";
  spit(file, s);
}

fs::path write_config(const fs::path& dir, const std::string& name, const fs::path& femur,
                      const fs::path& insert, const std::string& units) {
  const fs::path file = dir / (name + ".toml");
  spit(file, "[implant]\nkind = \"mesh\"\n[implant.mesh]\nfemur = \"" + femur.string() +
                 "\"\ninsert = \"" + insert.string() + "\"\nunits = \"" + units + "\"\n");
  return file;
}

}  // namespace

TEST_CASE("broken or mis-scaled meshes are refused by run and wear before any simulation") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const models::GenericTkrParams p;
  const models::TriMesh femur = models::make_generic_femur(p, 3e-3);
  const models::TriMesh insert = models::make_generic_insert(p, 3e-3);
  const fs::path f_m = tmp.path / "femur_m.stl", i_m = tmp.path / "insert_m.stl";
  const fs::path f_mm = tmp.path / "femur_mm.stl", i_mm = tmp.path / "insert_mm.stl";
  write_stl(f_m, femur, 1.0);
  write_stl(i_m, insert, 1.0);
  write_stl(f_mm, femur, 1e3);
  write_stl(i_mm, insert, 1e3);
  const fs::path i_nan = tmp.path / "insert_nan.stl", i_huge = tmp.path / "insert_huge.stl";
  const fs::path f_nan = tmp.path / "femur_nan.stl", f_huge = tmp.path / "femur_huge.stl";
  write_stl(i_nan, insert, 1.0, "nan");
  write_stl(i_huge, insert, 1.0, "1e30");
  write_stl(f_nan, femur, 1.0, "nan");
  write_stl(f_huge, femur, 1.0, "1e30");

  struct Case {
    const char* name;
    fs::path femur, insert;
    const char* units;
    std::vector<std::string> mentions;  // what the sentence must name
  };
  const std::vector<Case> cases = {
      {"NaN insert vertex", f_m, i_nan, "m", {"insert_nan.stl", "vertex 0", "nan", "finite"}},
      {"1e30 insert vertex", f_m, i_huge, "m", {"insert_huge.stl", "1e+30", "implant.mesh.units"}},
      {"NaN femur vertex", f_nan, i_m, "m", {"femur_nan.stl", "vertex 0", "finite"}},
      {"1e30 femur vertex", f_huge, i_m, "m", {"femur_huge.stl", "1e+30", "implant.mesh.units"}},
      {"mm meshes declared as m", f_mm, i_mm, "m", {"femur_mm.stl", "implant.mesh.units"}},
      {"mm insert declared as m", f_m, i_mm, "m", {"insert_mm.stl", "implant.mesh.units"}},
      {"m meshes declared as mm", f_m, i_m, "mm", {"femur_m.stl", "15-300 mm", "units = \"m\""}},
  };
  for (const Case& c : cases) {
    const std::string name = c.name;
    CAPTURE(name);
    const fs::path config = write_config(tmp.path, "case", c.femur, c.insert, c.units);
    for (const std::vector<std::string>& cmd :
         {std::vector<std::string>{"run", "--cycles", "1"},
          std::vector<std::string>{"wear", "--cycles", "2", "--update-every", "1"}}) {
      const fs::path out = tmp.path / ("out_" + cmd[0]);
      std::vector<std::string> args = cmd;
      args.insert(args.end(), {config.string(), "--quiet", "--out", out.string()});
      const Result r = run_kneesim(args, tmp.path);
      CAPTURE(cmd[0]);
      INFO("stderr: " << r.err);
      CHECK(r.exit_code == 2);
      CHECK(count_lines(r.err) == 1);
      for (const auto& m : c.mentions) CHECK_MESSAGE(r.err.find(m) != std::string::npos, m);
      CHECK_FALSE(fs::exists(out / "summary.json"));
      CHECK_FALSE(fs::exists(out / "kinematics.csv"));
      CHECK_FALSE(fs::exists(out / "wear.csv"));
    }
  }
  // control: the same meshes unbroken, in metres and in millimetres with their units, run
  // (--no-calibrate: these meshes have no calibrated law, and calibrating one on first use
  // would cost a deformable cycle; the run's contact law is not what is tested)
  for (const auto& [f, i, units] : {std::tuple{f_m, i_m, "m"}, std::tuple{f_mm, i_mm, "mm"}}) {
    const fs::path out = tmp.path / "good";
    const Result r = run_kneesim({"run", write_config(tmp.path, "good", f, i, units).string(),
                                  "--cycles", "1", "--quiet", "--no-calibrate", "--out",
                                  out.string()},
                                 tmp.path);
    INFO("stderr: " << r.err);
    CHECK(r.exit_code == 0);
    CHECK(fs::exists(out / "summary.json"));
  }
}
