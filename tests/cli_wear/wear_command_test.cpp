// `kneesim wear` as a user runs it (issue 3): the output set of a short coarse run; a run
// SIGKILLed as soon as its first checkpoint exists and continued with --resume
// writes a wear.csv byte-identical to the uninterrupted run's; a corrupt or foreign checkpoint
// is refused (exit 2, one line on stderr, the file left as it was, no summary.json); and every
// bad input of the list is one line on stderr and a non-zero exit.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "tests/cli_wear/cli_helpers.h"
#include "wear/checkpoint.h"

using namespace kneesim;
using namespace kneesim::test;

namespace {

// the refusal contract: exit 2 (InputError), one line on stderr naming what was wrong
void check_refused(const Result& r, const std::string& fragment, const fs::path& out) {
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK(count_lines(r.err) == 1);
  CHECK(r.err.rfind("error: ", 0) == 0);
  CHECK(r.err.find(fragment) != std::string::npos);
  CHECK_FALSE(fs::exists(out / "summary.json"));
}

}  // namespace

TEST_CASE("kneesim wear: outputs; killed and resumed gives a byte-identical wear.csv") {
  REQUIRE_MESSAGE(!find_kneesim().empty(), "kneesim not found above " << fs::read_symlink("/proc/self/exe"));
  TempDir tmp;
  const fs::path d1 = tmp.path / "D1", d2 = tmp.path / "D2";

  // uninterrupted reference
  const Result r1 = run_kneesim(wear_args(d1), tmp.path, "d1");
  INFO("stderr: " << r1.err);
  REQUIRE(r1.exit_code == 0);
  MESSAGE("kneesim wear 1 Mc / 4 updates, coarse: " << r1.seconds << " s wall (with plots)");
  const std::string csv1 = slurp(d1 / "wear.csv");
  {
    std::istringstream in(csv1);
    std::string header;
    std::getline(in, header);
    const std::vector<std::string> cols = split(header, ',');
    for (const char* c : {"cycles", "volume_mm3", "mass_mg", "max_depth_mm", "medial_volume_mm3",
                          "lateral_volume_mm3", "contact_area_mm2", "ap_rom_mm", "ie_rom_deg"}) {
      CHECK_MESSAGE(std::find(cols.begin(), cols.end(), c) != cols.end(), "missing column " << c);
    }
    // the IE range is in degrees and named so (issue 15: it was ie_rom_mm)
    CHECK(std::find(cols.begin(), cols.end(), "ie_rom_mm") == cols.end());
    CHECK(count_lines(csv1) == 6);  // header, cycle 0 and four updates
    const auto s = nlohmann::json::parse(slurp(d1 / "summary.json"));
    for (const char* k : {"wear_rate_mm3_per_Mc", "volume_mm3", "mass_mg", "max_depth_mm", "seconds"}) {
      REQUIRE_MESSAGE(s.contains(k), "summary.json lacks " << k);
      CHECK(s[k].is_number());
    }
    // UHMWPE on the default rig (issue 3 acceptance band 5-50 mm^3/Mc; simulators 15-25)
    MESSAGE("wear rate " << s["wear_rate_mm3_per_Mc"].get<double>() << " mm^3/Mc");
    CHECK(s["wear_rate_mm3_per_Mc"].get<double>() > 5.0);
    CHECK(s["wear_rate_mm3_per_Mc"].get<double>() < 50.0);
    // gravimetric = volumetric x density (physics.md section 6)
    CHECK(s["mass_mg"].get<double>() ==
          doctest::Approx(s["volume_mm3"].get<double>() * s["density_g_per_cm3"].get<double>()));
    for (const char* f : {"wear_depth_000000000.vtp", "wear_depth_000250000.vtp",
                          "wear_depth_001000000.vtp", "wear.png", "depth_map.png"}) {
      CHECK_MESSAGE(fs::exists(d1 / f), "missing " << f);
    }
    CHECK_FALSE(fs::exists(d1 / "wear.checkpoint"));  // a complete run leaves none behind
  }

  // killed as soon as the first checkpoint exists
  const Result k = kill_when_exists(wear_args(d2), tmp.path, d2 / "wear.checkpoint", "d2");
  REQUIRE_MESSAGE(k.signal == SIGKILL, "the run finished before it could be killed");
  CHECK_FALSE(fs::exists(d2 / "summary.json"));
  const std::string checkpoint = slurp(d2 / "wear.checkpoint");
  REQUIRE(checkpoint.size() > 100);

  {  // a corrupt or foreign checkpoint is refused and left in place
    struct Variant {
      std::string name;
      std::string bytes;
      std::vector<std::string> extra;
      std::string every;
      const char* fragment;
    };
    std::string flipped = checkpoint;
    flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x10);
    // a checkpoint of this very run (identity and hash valid) whose arrays do not fit the
    // model: what a changed mesh file behind an unchanged config would leave (the identity
    // hashes the config text, not the meshes it names)
    std::string misfit;
    {
      uint64_t identity = 0;
      std::memcpy(&identity, checkpoint.data() + 16, sizeof identity);  // after the magic
      wear::Checkpoint c = wear::read_checkpoint(d2 / "wear.checkpoint", identity);
      c.insert_vertices.resize(c.insert_vertices.size() / 2);
      c.vertex_depth.resize(c.vertex_depth.size() / 2);
      wear::write_checkpoint(tmp.path / "misfit.checkpoint", c);
      misfit = slurp(tmp.path / "misfit.checkpoint");
    }
    const std::vector<Variant> variants = {
        {"one byte flipped", flipped, {}, "250000", "corrupt"},
        {"truncated", checkpoint.substr(0, checkpoint.size() / 2), {}, "250000", "corrupt"},
        {"valid but of another mesh size", misfit, {}, "250000", "wear.checkpoint"},
        {"another run (--update-every 500000)", checkpoint, {}, "500000", "different wear run"},
        {"another run (--set gait.period_s=1.2)", checkpoint, {"--set", "gait.period_s=1.2"},
         "250000", "different wear run"},
    };
    for (const Variant& v : variants) {
      CAPTURE(v.name);
      spit(d2 / "wear.checkpoint", v.bytes);
      std::vector<std::string> extra = v.extra;
      extra.push_back("--resume");
      const Result r = run_kneesim(wear_args(d2, extra, v.every), tmp.path, "bad");
      check_refused(r, v.fragment, d2);
      CHECK(r.err.find("wear.checkpoint") != std::string::npos);
      CHECK(same_bytes(slurp(d2 / "wear.checkpoint"), v.bytes));  // not deleted, not overwritten
    }
    spit(d2 / "wear.checkpoint", checkpoint);  // the intact one back
  }

  {  // --resume continues to a byte-identical wear.csv
    const Result r = run_kneesim(wear_args(d2, {"--resume"}), tmp.path, "resume");
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(same_bytes(slurp(d2 / "wear.csv"), csv1));
    CHECK(same_bytes(slurp(d2 / "final_depth.csv"), slurp(d1 / "final_depth.csv")));
    const auto s = nlohmann::json::parse(slurp(d2 / "summary.json"));
    CHECK(s.contains("resumed_after_update"));
    CHECK_FALSE(fs::exists(d2 / "wear.checkpoint"));
  }
}

TEST_CASE("kneesim wear: bad input is one line on stderr and exit 2, nothing written") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path out = tmp.path / "out";
  struct Case {
    std::vector<std::string> args;
    const char* fragment;  // what the sentence must name
  };
  const std::vector<Case> cases = {
      {{"--cycles", "0"}, "--cycles: value '0' is not in the allowed range 1 to"},
      {{"--cycles", "-5"}, "--cycles: value '-5'"},
      {{"--cycles", "99999999999999999999"}, "allowed range 1 to 1000000000"},
      {{"--update-every", "1"}, "more than 10000 geometry updates"},
      {{"--update-every", "0"}, "--update-every: value '0' is not in the allowed range 1 to"},
      {{"--update-every", "-250000"}, "--update-every: value '-250000' is not in the allowed"},
      {{"--cycles", "1000000", "--update-every", "2000000"}, "larger than the run"},
      {{"--schedule", "0,250000"}, "--schedule: value '0' is not in the allowed range 1 to"},
      {{"--schedule", "250000,2000000"}, "--schedule entry 2000000"},
      {{"--material", "unobtainium"}, "unknown material 'unobtainium'"},
      {{"--set", "material.wear_factor_mm3_per_Nmm=1e-5"}, "--allow-any-wear-factor"},
      {{"--set", "material.wear_factor_mm3_per_Nmm=1e-13"}, "--allow-any-wear-factor"},
      // the deformable insert's mesh options are checked before any cycle
      {{"--set", "insert=deformable", "--set", "deformable.layers=41"}, "deformable.layers"},
  };
  for (const Case& c : cases) {
    std::string joined;
    for (const auto& a : c.args) joined += a + " ";
    CAPTURE(joined);
    std::vector<std::string> args = {"wear", "--out", out.string(), "--quiet",
                                     "--set", "implant.edge_length_mm=2"};
    // the base run is valid: each case's own option comes last and overrides it
    if (std::find(c.args.begin(), c.args.end(), "--cycles") == c.args.end()) {
      args.insert(args.end(), {"--cycles", "1000000"});
    }
    args.insert(args.end(), c.args.begin(), c.args.end());
    check_refused(run_kneesim(args, tmp.path), c.fragment, out);
  }
  // a file that is no checkpoint at all, with --resume
  fs::create_directories(out);
  spit(out / "wear.checkpoint", "this is not a checkpoint\n");
  check_refused(run_kneesim({"wear", "--out", out.string(), "--quiet", "--resume", "--cycles",
                             "1000000", "--set", "implant.edge_length_mm=2"},
                            tmp.path),
                "corrupt", out);
  // control: the override accepts the out-of-range factor (the refusal above is the range's);
  // --no-plots draws no PNG and writes the rest
  const Result ok = run_kneesim({"wear", "--out", out.string(), "--quiet", "--cycles", "2",
                                 "--update-every", "1", "--set", "implant.edge_length_mm=2",
                                 "--set", "material.wear_factor_mm3_per_Nmm=1e-5",
                                 "--allow-any-wear-factor", "--no-plots"},
                                tmp.path);
  INFO("stderr: " << ok.err);
  CHECK(ok.exit_code == 0);
  CHECK(fs::exists(out / "summary.json"));
  CHECK(fs::exists(out / "wear.csv"));
  CHECK_FALSE(fs::exists(out / "wear.png"));
  CHECK_FALSE(fs::exists(out / "depth_map.png"));
}

TEST_CASE("kneesim wear --convergence: one run per interval and the table against the finest") {
  // the update-interval study end to end (it had no CLI test): 4 cycles at intervals 2 and 1
  // on the coarse insert. Reference: the finest interval's row changes by exactly 0 %, each
  // interval's folder holds its own wear run, and --no-plots reaches every interval's job
  TempDir tmp;
  const fs::path out = tmp.path / "conv";
  const Result r = run_kneesim({"wear", "--out", out.string(), "--quiet", "--cycles", "4",
                                "--convergence", "2,1", "--set", "implant.edge_length_mm=2",
                                "--no-plots"},
                               tmp.path);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  const std::vector<std::string> lines = split(slurp(out / "convergence.csv"), '\n');
  REQUIRE(lines.size() >= 3);
  const std::vector<std::string> cols = split(lines[0], ',');
  const auto col = [&](const char* name) {
    return std::find(cols.begin(), cols.end(), name) - cols.begin();
  };
  REQUIRE(col("volume_change_pct") < static_cast<long>(cols.size()));
  for (size_t i = 1; i <= 2; ++i) {
    const std::vector<std::string> row = split(lines[i], ',');
    REQUIRE(row.size() == cols.size());
    const long every = std::lround(std::stod(row[col("update_every")]));
    CAPTURE(every);
    CHECK(std::stod(row[col("updates")]) == doctest::Approx(4.0 / every));
    CHECK(std::stod(row[col("volume_mm3")]) > 0.0);
    if (every == 1) CHECK(std::stod(row[col("volume_change_pct")]) == 0.0);
    const fs::path dir = out / ("every_" + std::to_string(every));
    CHECK(fs::exists(dir / "wear.csv"));
    CHECK(fs::exists(dir / "summary.json"));
    CHECK_FALSE(fs::exists(dir / "wear.png"));
  }
  CHECK(fs::exists(out / "convergence.md"));
}
