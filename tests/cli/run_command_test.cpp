// `kneesim run` as a user runs it: the built program is started as a subprocess (found in the
// build tree beside this test: <build>/tests/cli/test_cli -> <build>/tools/kneesim), and its
// exit code, stderr and output folder are checked against the issue-2 contract:
// kinematics.csv (one row per 1 % of the last cycle, the required columns), summary.json (the
// required keys), .vtp pressure maps and kinematics.png; bad input exits non-zero with one
// line on stderr and leaves no summary.json.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/cli_wear/cli_helpers.h"  // find_kneesim, run_kneesim, TempDir, slurp, split

namespace fs = std::filesystem;
using namespace kneesim::test;

namespace {

// models/examples/<name> when the Grand Challenge JW meshes are in $KNEESIM_DATA, else empty
// (the caller skips)
std::string find_jw_example(const char* name) {
  const char* data = std::getenv("KNEESIM_DATA");
  const char* source = std::getenv("KNEESIM_SOURCE_DIR");
  if (data == nullptr || source == nullptr ||
      !fs::exists(fs::path(data) / "gc4_jw/femoral_component.stl")) {
    MESSAGE("skipped: the JW meshes are not in $KNEESIM_DATA");
    return {};
  }
  return (fs::path(source) / "models/examples" / name).string();
}

}  // namespace

TEST_CASE("kneesim run writes the complete result set") {
  TempDir tmp;
  const fs::path out = tmp.path / "result";
  // the built-in default at a coarse insert (2 mm edges) to keep the test fast
  const Result r = run_kneesim({"run", "--out", out.string(), "--set", "implant.edge_length_mm=2"},
                               tmp.path);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);

  // kinematics.csv: header with the required columns, one row per 1 % of the last cycle
  std::ifstream csv(out / "kinematics.csv");
  REQUIRE(csv.good());
  std::string header;
  std::getline(csv, header);
  const std::vector<std::string> cols = split(header, ',');
  for (const char* c : {"gait_pct", "flexion_deg", "ap_mm", "ie_deg", "ml_mm", "vv_deg",
                        "axial_force_N", "contact_force_N", "medial_force_N", "lateral_force_N",
                        "contact_area_mm2", "peak_pressure_MPa"}) {
    CHECK_MESSAGE(std::find(cols.begin(), cols.end(), c) != cols.end(), "missing column " << c);
  }
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(csv, line);) {
    if (!line.empty()) rows.push_back(split(line, ','));
  }
  CHECK((rows.size() == 100 || rows.size() == 101));

  // summary.json with the required keys, all finite numbers, and plausible values
  const auto summary = nlohmann::json::parse(slurp(out / "summary.json"));
  for (const char* k : {"ap_rom_mm", "ie_rom_deg", "peak_pressure_MPa", "mean_peak_pressure_MPa",
                        "seconds_per_cycle", "steps_per_cycle"}) {
    REQUIRE_MESSAGE(summary.contains(k), "summary.json lacks " << k);
    CHECK(summary[k].is_number());
  }
  CHECK(summary["ap_rom_mm"].get<double>() > 0.0);
  CHECK(summary["ie_rom_deg"].get<double>() > 0.0);
  // the first release's misnamed key stays one release as an alias of the same value (README)
  CHECK(summary["ie_rom_mm"] == summary["ie_rom_deg"]);
  CHECK(summary["peak_pressure_MPa"].get<double>() >=
        summary["mean_peak_pressure_MPa"].get<double>());
  CHECK(summary["steps_per_cycle"].get<double>() >= 100.0);
  // rows at every 1 % of the cycle: each row is the step nearest its percentage, so within
  // half a step (50 / steps_per_cycle %); the first row is the 0 % row (not 100 %)
  const double half_step_pct = 50.0 / summary["steps_per_cycle"].get<double>();
  const auto pct_col = std::find(cols.begin(), cols.end(), "gait_pct") - cols.begin();
  for (size_t i = 0; i < rows.size(); ++i) {
    REQUIRE(rows[i].size() == cols.size());
    const double pct = std::stod(rows[i][pct_col]);
    CAPTURE(i);
    // + 1e-6 %: the CSV's gait_pct is printed to 7 significant digits, and a row exactly half
    // a step from its percentage (a tie) prints its rounding
    CHECK(std::abs(pct - static_cast<double>(i)) <= half_step_pct + 1e-6);
  }
  MESSAGE("kneesim run (edge 2 mm): AP ROM " << summary["ap_rom_mm"] << " mm, IE ROM "
          << summary["ie_rom_deg"] << " deg, peak pressure " << summary["peak_pressure_MPa"]
          << " MPa, " << summary["seconds_per_cycle"] << " s per cycle, "
          << summary["steps_per_cycle"] << " steps per cycle");

  // pressure maps (VTK PolyData XML) and the plot (PNG signature)
  int vtp = 0;
  for (const auto& e : fs::directory_iterator(out)) {
    if (e.path().extension() == ".vtp") {
      ++vtp;
      CHECK(slurp(e.path()).find("<VTKFile") != std::string::npos);
    }
  }
  CHECK(vtp >= 1);
  const std::string png = slurp(out / "kinematics.png");
  REQUIRE(png.size() > 8);
  CHECK(png.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
}

TEST_CASE("kneesim run with the coupled rig step runs end to end and says so") {
  // solver.rig_coupling = "coupled" (engine/rig_coupling.h) on the built-in implant at 2 mm
  // edges; reference: the partitioned step's ranges on the same model. The two steps' errors
  // differ by a few per cent on this rig (docs/validation.md, "Rig step": IE +0.8 and +2.3 %
  // against CVODE at 1 mm edges), so 10 %: a check against
  // a wrong sign or frame in the coupled rows, not of accuracy (the validation case is that)
  TempDir tmp;
  const fs::path coupled = tmp.path / "coupled", partitioned = tmp.path / "partitioned";
  const Result a = run_kneesim({"run", "--out", coupled.string(), "--no-plots", "--set",
                                "implant.edge_length_mm=2", "--set", "solver.rig_coupling=coupled"},
                               tmp.path);
  INFO("stderr: " << a.err);
  REQUIRE(a.exit_code == 0);
  const Result b = run_kneesim({"run", "--out", partitioned.string(), "--no-plots", "--set",
                                "implant.edge_length_mm=2"},
                               tmp.path);
  REQUIRE(b.exit_code == 0);
  const auto sa = nlohmann::json::parse(slurp(coupled / "summary.json"));
  const auto sb = nlohmann::json::parse(slurp(partitioned / "summary.json"));
  CHECK(sa["rig_coupling"] == "coupled");
  CHECK(sb["rig_coupling"] == "partitioned");
  CHECK(sa["status"] == "complete");
  CHECK(sa["ap_rom_mm"].get<double>() ==
        doctest::Approx(sb["ap_rom_mm"].get<double>()).epsilon(0.10));
  CHECK(sa["ie_rom_deg"].get<double>() ==
        doctest::Approx(sb["ie_rom_deg"].get<double>()).epsilon(0.10));
  // a value that does not exist: one sentence naming the key and the choices, exit 2
  const Result bad = run_kneesim({"run", "--out", (tmp.path / "bad").string(), "--set",
                                  "solver.rig_coupling=implicit"},
                                 tmp.path);
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("solver.rig_coupling") != std::string::npos);
  CHECK(bad.err.find("coupled") != std::string::npos);
}

TEST_CASE("a coupled rig step that runs away says how to repeat it") {
  // the JW measured loads with a 3.75 mm medial load-line shift (skipped without
  // $KNEESIM_DATA): the coupled step runs away at the default step at t = 0.58 s while CVODE
  // and a quarter of the step complete (docs/validation.md, rig step); the one-line error
  // names the remedy, and the frames up to the failure are kept (one cycle asked)
  const std::string config = find_jw_example("jw_measured_loads.toml");
  if (config.empty()) return;
  TempDir tmp;
  const fs::path out = tmp.path / "coupled";
  const Result r = run_kneesim(
      {"run", config, "--out", out.string(), "--no-plots", "--quiet", "--cycles", "1", "--set",
       "implant.mesh.femur_origin_mm=[-3.8, 1.7, 0.0]", "--set",
       "gait.vv_torque_axial_arm_mm=3.75", "--set", "solver.rig_coupling=coupled"},
      tmp.path);
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 1);
  CHECK(count_lines(without_contact_law_warning(r.err)) == 1);
  CHECK(r.err.find("runaway motion") != std::string::npos);
  CHECK(r.err.find("solver.dt_safety=0.2") != std::string::npos);
  CHECK(r.err.find("the frames completed so far are in") != std::string::npos);
  CHECK(count_lines(slurp(out / "kinematics.partial.csv")) > 40);
}

TEST_CASE("kneesim run refines an imported femur on request, and refuses too fine a target") {
  // the Grand Challenge JW meshes (skipped without $KNEESIM_DATA): implant.mesh.femur_refine_mm
  // (models/smooth_refine.h) runs end to end, and each level quarters the femur's triangles
  const std::string config = find_jw_example("jw_stanmore.toml");
  if (config.empty()) return;
  TempDir tmp;
  const fs::path plain = tmp.path / "plain", refined = tmp.path / "refined";
  const Result a = run_kneesim({"run", config, "--out", plain.string(), "--no-plots", "--quiet",
                                "--cycles", "1"},
                               tmp.path);
  REQUIRE(a.exit_code == 0);
  // a target just under the median edge (0.44 mm): one level
  const Result b = run_kneesim({"run", config, "--out", refined.string(), "--no-plots", "--quiet",
                                "--cycles", "1", "--set", "implant.mesh.femur_refine_mm=0.4"},
                               tmp.path);
  INFO("stderr: " << b.err);
  REQUIRE(b.exit_code == 0);
  const auto sa = nlohmann::json::parse(slurp(plain / "summary.json"));
  const auto sb = nlohmann::json::parse(slurp(refined / "summary.json"));
  const auto ta = sa["femur_triangles"].get<long>(), tb = sb["femur_triangles"].get<long>();
  CHECK(tb == 4 * ta);
  CHECK(sb["femur_refine_mm"] == 0.4);
  CHECK(sb["status"] == "complete");
  // the refined femur is the same implant: the pressures move by a few per cent, not more
  CHECK(sb["peak_pressure_MPa"].get<double>() ==
        doctest::Approx(sa["peak_pressure_MPa"].get<double>()).epsilon(0.25));
  // too fine for the allowed size: one sentence naming the key and the finest allowed target
  const Result bad = run_kneesim({"run", config, "--out", (tmp.path / "bad").string(),
                                  "--set", "implant.mesh.femur_refine_mm=0.001"},
                                 tmp.path);
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("implant.mesh.femur_refine_mm") != std::string::npos);
  CHECK(bad.err.find(">=") != std::string::npos);
}

TEST_CASE("the first row of kinematics.csv is the 0 % row") {
  // at 3 mm edges the step count per cycle makes the accumulated time land just below 1 s at
  // the start of the last cycle; the row must still read 0 %, not 100 %
  TempDir tmp;
  const fs::path out = tmp.path / "result";
  const Result r = run_kneesim(
      {"run", "--out", out.string(), "--quiet", "--set", "implant.edge_length_mm=3"}, tmp.path);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  std::ifstream csv(out / "kinematics.csv");
  std::string header, first;
  std::getline(csv, header);
  std::getline(csv, first);
  const auto cols = split(header, ',');
  const auto pct_col = std::find(cols.begin(), cols.end(), "gait_pct") - cols.begin();
  const double pct = std::stod(split(first, ',')[pct_col]);
  CHECK(pct >= 0.0);
  CHECK(pct < 0.1);
}

TEST_CASE("--no-plots skips the plot and nothing else") {
  // the same one-cycle run twice: the plot is the only difference (the timing measure of
  // docs/performance.md takes the plot out of `run --cycles 11` minus `--cycles 1`)
  TempDir tmp;
  const fs::path with = tmp.path / "with", without = tmp.path / "without";
  for (const auto& [out, flag] : {std::pair{with, ""}, std::pair{without, "--no-plots"}}) {
    std::vector<std::string> args = {"run", "--out", out.string(), "--quiet", "--cycles", "1",
                                     "--set", "implant.edge_length_mm=3"};
    if (*flag != 0) args.emplace_back(flag);
    const Result r = run_kneesim(args, tmp.path);
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
  }
  CHECK(fs::exists(with / "kinematics.png"));
  CHECK_FALSE(fs::exists(without / "kinematics.png"));
  CHECK(fs::exists(without / "summary.json"));
  CHECK(slurp(with / "kinematics.csv") == slurp(without / "kinematics.csv"));
}

TEST_CASE("kneesim run rejects bad input with one line and no summary") {
  TempDir tmp;
  fs::path bad_config = tmp.path / "negative_modulus.toml";
  std::ofstream(bad_config) << "[material]\nelastic_modulus_MPa = -5\n";
  const fs::path measured_bad = tmp.path / "ap_only.csv";
  std::ofstream(measured_bad) << "gait_pct,ap_mm\n0,1\n50,2\n";
  struct Case {
    const char* name;
    std::vector<std::string> args;
    std::vector<std::string> mentions;  // substrings the message must contain
  };
  const std::vector<Case> cases = {
      {"unknown key", {"--set", "contact.no_such_key=1"}, {"contact.no_such_key"}},
      {"unknown preset", {"--set", "rig.preset=foo"}, {"rig.preset", "foo", "stanmore"}},
      {"missing config file", {(tmp.path / "missing.toml").string()}, {"missing.toml"}},
      {"negative modulus", {bad_config.string()},
       {"negative_modulus.toml", "elastic_modulus_MPa", "-5"}},
      {"friction outside [0, 1]", {"--set", "material.friction=1.5"}, {"material.friction", "1.5"}},
      {"bad --set syntax", {"--set", "no_equals_sign"}, {"no_equals_sign"}},
      // CLI11 parse errors exit 2 too (issue 15: they were 104-114), with a readable range
      {"--cycles 0", {"--cycles", "0"}, {"--cycles", "0", "1 to 1000000"}},
      {"unknown flag", {"--no-such-flag"}, {"--no-such-flag"}},
      // the measured file is checked before the simulation: nothing is written
      {"measured file without ie_deg", {"--measured", measured_bad.string()},
       {"ap_only.csv", "ie_deg", "gait_pct, ap_mm, ie_deg"}},
  };
  for (const Case& c : cases) {
    const std::string name = c.name;
    CAPTURE(name);
    const fs::path out = tmp.path / "out";
    std::vector<std::string> args = {"run", "--out", out.string()};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const Result r = run_kneesim(args, tmp.path);
    INFO("stderr: " << r.err);
    CHECK(r.exit_code == 2);
    CHECK(count_lines(r.err) == 1);
    for (const auto& m : c.mentions) CHECK_MESSAGE(r.err.find(m) != std::string::npos, m);
    CHECK_FALSE(fs::exists(out / "summary.json"));
    CHECK_FALSE(fs::exists(out / "kinematics.csv"));
  }
}

TEST_CASE("an unknown command is bad input: exit 2 naming it and the commands") {
  TempDir tmp;
  const Result r = run_kneesim({"bogus"}, tmp.path);
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 2);
  CHECK(count_lines(r.err) == 1);
  CHECK(r.err.find("'bogus' is not a kneesim command; the commands are run,") != std::string::npos);
  CHECK(run_kneesim({"--help"}, tmp.path).exit_code == 0);
}

TEST_CASE("the documented 3-column measured CSV overlays a run") {
  TempDir tmp;
  const fs::path measured = tmp.path / "m.csv";
  std::ofstream(measured) << "gait_pct,ap_mm,ie_deg\n0,1,2\n50,-1,4\n";
  const fs::path out = tmp.path / "out";
  const Result r = run_kneesim({"run", "--out", out.string(), "--quiet", "--cycles", "1", "--set",
                                "implant.edge_length_mm=3", "--measured", measured.string()},
                               tmp.path);
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 0);
  CHECK(split(slurp(out / "measured_kinematics.csv"), '\n').front() == "gait_pct,ap_mm,ie_deg");
}

TEST_CASE("a run that fails numerically leaves no complete-looking result") {
  // a 2 MPa insert cannot carry the gait load: the femur sinks through the elastic layer and
  // the engine stops with runaway penetration; the CLI must exit non-zero with one line and
  // keep only the partial files (kinematics.partial.csv, summary.failed.json)
  TempDir tmp;
  const fs::path out = tmp.path / "out";
  // (contact.calibration = "auto": the law as specified, where the default would first calibrate
  // one for this material against the deformable insert)
  const Result r = run_kneesim({"run", "--out", out.string(), "--quiet", "--set",
                                "implant.edge_length_mm=3", "--set",
                                "material.elastic_modulus_MPa=2", "--set",
                                "contact.calibration=auto"},
                               tmp.path);
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 1);  // numerical trouble, not bad input
  // a 2 MPa material has no calibrated law: the law as specified, said in one warning line
  CHECK(r.err.find("warning: no calibrated contact law") != std::string::npos);
  CHECK(count_lines(without_contact_law_warning(r.err)) == 1);
  CHECK(r.err.find("runaway") != std::string::npos);
  // it stops in the first of two cycles, before the frames (the last cycle's) begin: the
  // message says no frame was kept and how to keep them, not that the empty table holds them
  CHECK(r.err.find("no frame was kept") != std::string::npos);
  CHECK(r.err.find("--cycles 1 keeps the frames") != std::string::npos);
  CHECK_FALSE(fs::exists(out / "summary.json"));
  CHECK_FALSE(fs::exists(out / "kinematics.csv"));
  CHECK_FALSE(fs::exists(out / "kinematics.png"));
  CHECK(fs::exists(out / "summary.failed.json"));
  // a good run into the same folder leaves no stale failure record beside its summary
  const Result good = run_kneesim({"run", "--out", out.string(), "--quiet", "--cycles", "1",
                                   "--set", "implant.edge_length_mm=3"},
                                  tmp.path);
  CHECK(good.exit_code == 0);
  CHECK(fs::exists(out / "summary.json"));
  CHECK_FALSE(fs::exists(out / "summary.failed.json"));
  CHECK_FALSE(fs::exists(out / "kinematics.partial.csv"));
}

TEST_CASE("kneesim run with the deformable insert writes the rigid outputs plus stresses") {
  // smoke test: a coarse insert (3 mm elements, 3 layers) over one 0.2 s cycle; the same files
  // as the rigid path plus insert_stress.vtu, the pressure maps with node pressures and the
  // element fields, and the summary's stress, plastic-strain and energy-ratio keys
  TempDir tmp;
  const fs::path out = tmp.path / "result";
  const Result r = run_kneesim(
      {"run", "--out", out.string(), "--quiet", "--cycles", "1", "--set", "insert=deformable",
       "--set", "deformable.element_size_mm=3", "--set", "deformable.layers=3", "--set",
       "implant.edge_length_mm=2", "--set", "gait.period_s=0.2", "--set", "solver.threads=2"},
      tmp.path);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(fs::exists(out / "kinematics.csv"));
  CHECK(fs::exists(out / "kinematics.png"));
  const auto summary = nlohmann::json::parse(slurp(out / "summary.json"));
  for (const char* k : {"ap_rom_mm", "ie_rom_mm", "peak_pressure_MPa", "mean_contact_area_mm2",
                        "von_mises_max_surface_MPa", "von_mises_max_subsurface_MPa",
                        "plastic_strain_max_surface", "plastic_strain_max_subsurface",
                        "kinetic_to_internal_max", "kinetic_to_internal_max_after_settling",
                        "settling_s", "solid_elements", "solid_added_mass_kg"}) {
    REQUIRE_MESSAGE(summary.contains(k), "summary.json lacks " << k);
    CHECK(summary[k].is_number());
  }
  // one cycle from rest: its first 1 % is the settling (0.2 s period)
  CHECK(summary["settling_s"].get<double>() == doctest::Approx(0.002).epsilon(0.02));
  CHECK(summary["kinetic_to_internal_max_after_settling"].get<double>() <=
        summary["kinetic_to_internal_max"].get<double>());
  CHECK(summary["peak_pressure_MPa"].get<double>() > 0.0);
  CHECK(summary["von_mises_max_subsurface_MPa"].get<double>() > 0.0);
  const std::string vtu = slurp(out / "insert_stress.vtu");
  CHECK(vtu.find("UnstructuredGrid") != std::string::npos);
  CHECK(vtu.find("von_mises_max_MPa") != std::string::npos);
  CHECK(vtu.find("plastic_strain") != std::string::npos);
  const std::string map = slurp(out / "pressure_013pct.vtp");
  CHECK(map.find("pressure_MPa") != std::string::npos);
  CHECK(map.find("von_mises_max_MPa") != std::string::npos);
}

TEST_CASE("an inverting element stops a deformable run with exit 1, naming it and the time") {
  // a 2 MPa insert cannot carry the gait load: a top element is crushed through zero volume
  // within the first centiseconds; only the partial files remain
  TempDir tmp;
  const fs::path out = tmp.path / "out";
  const Result r = run_kneesim(
      {"run", "--out", out.string(), "--quiet", "--cycles", "1", "--set", "insert=deformable",
       "--set", "deformable.element_size_mm=3", "--set", "deformable.layers=3", "--set",
       "implant.edge_length_mm=2", "--set", "gait.period_s=0.2", "--set",
       "material.elastic_modulus_MPa=2"},
      tmp.path);
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 1);
  CHECK(count_lines(r.err) == 1);
  CHECK(r.err.find("element ") != std::string::npos);
  CHECK(r.err.find("inverted") != std::string::npos);
  CHECK(r.err.find("t = ") != std::string::npos);
  CHECK_FALSE(fs::exists(out / "summary.json"));
  CHECK_FALSE(fs::exists(out / "insert_stress.vtu"));
  CHECK(fs::exists(out / "insert_stress.partial.vtu"));
  CHECK(fs::exists(out / "kinematics.partial.csv"));
  const auto failed = nlohmann::json::parse(slurp(out / "summary.failed.json"));
  CHECK(failed["inverted_element"].get<int>() >= 0);
}
