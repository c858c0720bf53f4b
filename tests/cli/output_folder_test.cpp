// The output folder of every command is checked before any work (issue 15: an --out that was a
// file or not writable leaked a raw "filesystem error" with exit 1, after the simulation for
// some commands). Contract: exit 2, one sentence naming --out, the folder and what is wrong,
// within a second or so (nothing simulated), no result files. Also: a compare into a folder of
// an earlier compare keeps no result folder of a material it did not run, and a failed wear
// run followed by a good one leaves no failure record beside the summary.
#include <doctest/doctest.h>

#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/cli_wear/cli_helpers.h"  // find_kneesim, run_kneesim, TempDir, slurp

namespace fs = std::filesystem;
using namespace kneesim::test;

namespace {

// each command with the fewest arguments that pass its parser; the --out check comes first in
// every callback, so the files need not hold valid data
std::vector<std::vector<std::string>> every_command(const fs::path& dummy) {
  const std::string d = dummy.string();
  return {{"run"},
          {"wear"},
          {"compare"},
          {"particles"},
          {"bor"},
          {"study"},
          {"diagnose", "bor", "--measured", d},
          {"diagnose", "knee-wear", "--measured", d, "--config", d},
          {"diagnose", "kinematics", "--measured", d, "--config", d},
          {"diagnose", "forces", "--config", d}};
}

void check_out_refused(std::vector<std::string> args, const fs::path& out, const fs::path& cwd,
                       const std::string& fragment) {
  args.insert(args.end(), {"--out", out.string()});
  std::string joined;
  for (const auto& a : args) joined += a + " ";
  CAPTURE(joined);
  const Result r = run_kneesim(args, cwd);
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 2);
  CHECK(count_lines(r.err) == 1);
  CHECK(r.err.find("--out '" + out.string() + "'") != std::string::npos);
  CHECK(r.err.find(fragment) != std::string::npos);
  CHECK(r.err.find("filesystem error") == std::string::npos);
}

}  // namespace

TEST_CASE("every command refuses an --out that is a file, before any work") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path file = tmp.write("a_file", "x\n");
  for (const auto& cmd : every_command(file)) {
    check_out_refused(cmd, file, tmp.path, "is an existing file, not a folder");
    std::string in_the_way = "'";  // (built in steps: GCC 12 warns -Wrestrict on "'" + s)
    in_the_way += file.string();
    in_the_way += "' is a file";
    check_out_refused(cmd, file / "sub", tmp.path, in_the_way);
  }
  CHECK(slurp(file) == "x\n");  // left as it was
}

TEST_CASE("every command refuses an --out it cannot write, before any work") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path locked = tmp.path / "locked";
  fs::create_directories(locked);
  // permission bits stop an ordinary user; root needs the immutable attribute (ext4, xfs)
  ::chmod(locked.c_str(), 0555);
  bool unwritable = ::access(locked.c_str(), W_OK) != 0;
  const std::string chattr = "chattr +i '" + locked.string() + "' 2>/dev/null";
  bool immutable = false;
  if (!unwritable) immutable = unwritable = std::system(chattr.c_str()) == 0;
  if (!unwritable) {
    MESSAGE("skipped: no way to make a folder unwritable here (root without chattr)");
    return;
  }
  for (const auto& cmd : every_command(tmp.write("dummy", "x\n"))) {
    check_out_refused(cmd, locked, tmp.path, "is not writable");
    check_out_refused(cmd, locked / "sub", tmp.path, "cannot be created");
  }
  if (immutable) CHECK(std::system(("chattr -i '" + locked.string() + "'").c_str()) == 0);
  ::chmod(locked.c_str(), 0755);
  CHECK(fs::is_empty(locked));
}

TEST_CASE("compare into an earlier compare's folder keeps only this comparison") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path out = tmp.path / "cmp";
  const std::vector<std::string> base = {"compare", "--cycles", "2", "--update-every", "1",
                                         "--set", "implant.edge_length_mm=3", "--quiet",
                                         "--out", out.string()};
  auto with = [&](const std::string& materials) {
    std::vector<std::string> a = base;
    a.insert(a.end(), {"--materials", materials});
    return a;
  };
  Result r = run_kneesim(with("uhmwpe,peek"), tmp.path);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  REQUIRE(fs::exists(out / "peek" / "summary.json"));
  // a folder of the user's own inside --out is not a result folder: it stays
  fs::create_directories(out / "notes");
  tmp.write("cmp/notes/readme.txt", "mine\n");
  r = run_kneesim(with("uhmwpe"), tmp.path);
  REQUIRE(r.exit_code == 0);
  CHECK(fs::exists(out / "uhmwpe" / "summary.json"));
  CHECK_FALSE(fs::exists(out / "peek"));
  CHECK(fs::exists(out / "notes" / "readme.txt"));
  CHECK(slurp(out / "comparison.csv").find("peek") == std::string::npos);
}

TEST_CASE("a failed wear run keeps a partial table; a good run after it leaves no failure record") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path out = tmp.path / "w";
  const std::vector<std::string> base = {"wear", "--cycles", "2", "--update-every", "1",
                                         "--set", "implant.edge_length_mm=3", "--quiet",
                                         "--out", out.string()};
  // a 2 MPa insert cannot carry the gait load: runaway penetration in the first cycle
  std::vector<std::string> bad = base;
  // (contact.calibration = "auto": no calibration on first use for this material)
  bad.insert(bad.end(), {"--set", "material.elastic_modulus_MPa=2", "--set",
                         "contact.calibration=auto"});
  const Result failed = run_kneesim(bad, tmp.path);
  INFO("stderr: " << failed.err);
  CHECK(failed.exit_code == 1);
  // a 2 MPa material has no calibrated law: the law as specified, said in one warning line
  CHECK(failed.err.find("warning: no calibrated contact law") != std::string::npos);
  CHECK(count_lines(without_contact_law_warning(failed.err)) == 1);
  CHECK(failed.err.find("runaway") != std::string::npos);
  CHECK(failed.err.find("no geometry update was completed") != std::string::npos);
  CHECK(fs::exists(out / "summary.failed.json"));
  CHECK_FALSE(fs::exists(out / "summary.json"));
  CHECK_FALSE(fs::exists(out / "wear.csv"));  // no complete-looking table
  const Result good = run_kneesim(base, tmp.path);
  CHECK(good.exit_code == 0);
  CHECK(fs::exists(out / "summary.json"));
  CHECK(fs::exists(out / "wear.csv"));
  CHECK_FALSE(fs::exists(out / "summary.failed.json"));
  CHECK_FALSE(fs::exists(out / "wear.partial.csv"));
}

TEST_CASE("wear --no-depth-maps writes no depth maps") {
  // the switch the output-size refusal suggests (a run whose maps would not fit in the free
  // space of --out is refused with the estimate before the first cycle)
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path out = tmp.path / "w";
  const Result r = run_kneesim({"wear", "--cycles", "2", "--update-every", "1", "--set",
                                "implant.edge_length_mm=3", "--quiet", "--no-depth-maps",
                                "--out", out.string()},
                               tmp.path);
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 0);
  CHECK(fs::exists(out / "summary.json"));
  for (const auto& e : fs::directory_iterator(out)) {
    CHECK(e.path().filename().string().rfind("wear_depth_", 0) != 0);
  }
}
