// `kneesim wear` and `kneesim compare` with insert = "deformable" (issue 11 item 5), end to end
// on a coarse insert (3 mm elements, 3 layers, 2 mm implant, 0.2 s gait cycle): the rigid
// path's outputs plus the von Mises and plastic-strain maxima (surface and subsurface) in
// wear.csv, summary.json and comparison.csv, and per element in insert_stress.vtu and
// wear_surface.vtp. References: the volume bookkeeping of the rigid path (hex volume loss
// against the depth integral, 1 %), the summary agreeing with the table's rows, and the
// materials' order of the rigid path (CFR-PEEK, the stiffest, carries the highest pressure).
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/cli_wear/cli_helpers.h"

using namespace kneesim::test;

namespace {

// The gait runs 5x fast (0.2 s) to keep the test short. At that speed the rig's light IE
// (3e-5 kg m^2) releases fast enough to shake the mass-scaled solid: kinetic / internal energy
// 8.6 % at its maximum, against 0.1 % at the real 1 s gait (measured, 3 mm elements). The test
// checks the deformable outputs, not the rig, so it keeps the heavier 0.01 kg m^2 IE inertia
// (0.8 % at 0.2 s).
const std::vector<std::string> kCoarse = {
    "--set", "insert=deformable",       "--set", "deformable.element_size_mm=3",
    "--set", "deformable.layers=3",     "--set", "implant.edge_length_mm=2",
    "--set", "gait.period_s=0.2",       "--set", "rig.ie_inertia_kgm2=0.01"};

// header and rows of a CSV file written by kneesim (first column may be a label)
struct Csv {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
  int column(const std::string& name) const {
    for (size_t i = 0; i < columns.size(); ++i)
      if (columns[i] == name) return static_cast<int>(i);
    return -1;
  }
};

Csv read_csv(const fs::path& p) {
  Csv c;
  std::istringstream in(slurp(p));
  std::string line;
  auto split = [](const std::string& l) {
    std::vector<std::string> cells;
    std::stringstream ss(l);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    return cells;
  };
  if (std::getline(in, line)) c.columns = split(line);
  while (std::getline(in, line))
    if (!line.empty()) c.rows.push_back(split(line));
  return c;
}

}  // namespace

TEST_CASE("kneesim wear --set insert=deformable writes the rigid outputs plus stresses") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path out = tmp.path / "out";
  std::vector<std::string> args = {"wear", "--out", out.string(), "--quiet", "--cycles",
                                   "1000000", "--update-every", "500000"};
  args.insert(args.end(), kCoarse.begin(), kCoarse.end());
  const Result r = run_kneesim(args, tmp.path);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  MESSAGE("kneesim wear, deformable, 1 Mc / 2 updates, coarse: " << r.seconds << " s wall");
  for (const char* f : {"wear.csv", "summary.json", "final_depth.csv", "kinematics.csv",
                        "wear.png", "depth_map.png", "insert_stress.vtu", "wear_surface.vtp",
                        "wear_depth_000000000.vtp", "wear_depth_001000000.vtp"}) {
    CHECK_MESSAGE(fs::exists(out / f), f);
  }
  CHECK_FALSE(fs::exists(out / "wear.checkpoint"));
  const Csv csv = read_csv(out / "wear.csv");
  REQUIRE(csv.rows.size() == 3);
  for (const char* c : {"volume_mm3", "volume_depth_mm3", "max_depth_mm", "peak_pressure_MPa",
                        "von_mises_max_surface_MPa", "von_mises_max_subsurface_MPa",
                        "plastic_strain_max_surface", "plastic_strain_max_subsurface"}) {
    CHECK_MESSAGE(csv.column(c) >= 0, c);
  }
  const auto s = nlohmann::json::parse(slurp(out / "summary.json"));
  CHECK(s["status"] == "complete");
  CHECK(s["insert"] == "deformable");
  const double volume = s["volume_mm3"].get<double>();
  CHECK(volume > 0.0);
  CHECK(std::abs(s["volume_bookkeeping_rel_diff"].get<double>()) < 0.01);
  CHECK(
      volume ==
      doctest::Approx(std::stod(csv.rows.back()[csv.column("volume_mm3")])).epsilon(1e-6).scale(0));
  for (const char* k : {"von_mises_max_surface_MPa", "von_mises_max_subsurface_MPa",
                        "final_von_mises_max_surface_MPa", "contact_area_mm2",
                        "peak_pressure_MPa", "solid_elements"}) {
    REQUIRE_MESSAGE(s.contains(k), k);
    CHECK(s[k].get<double>() > 0.0);
  }
  for (const char* k : {"plastic_strain_max_surface", "plastic_strain_max_subsurface",
                        "final_plastic_strain_max_surface", "final_plastic_strain_max_subsurface"}) {
    REQUIRE_MESSAGE(s.contains(k), k);
    CHECK(s[k].get<double>() >= 0.0);
  }
  // the quasi-static validity of the mass-scaled insert, as `kneesim run` reports it (issue 11:
  // kinetic below 5 % of the internal energy)
  for (const char* k : {"kinetic_to_internal_max", "kinetic_to_internal_cycle",
                        "final_kinetic_to_internal_max", "final_kinetic_to_internal_cycle",
                        "kinetic_to_internal_max_all_cycles"}) {
    REQUIRE_MESSAGE(s.contains(k), k);
    CHECK_MESSAGE(s[k].get<double>() > 0.0, k);
    CHECK_MESSAGE(s[k].get<double>() < 0.05, k);
  }
  CHECK(s["kinetic_to_internal_max_all_cycles"].get<double>() >=
        s["final_kinetic_to_internal_max"].get<double>());
  const std::string vtu = slurp(out / "insert_stress.vtu");
  CHECK(vtu.find("von_mises_max_MPa") != std::string::npos);
  CHECK(vtu.find("plastic_strain") != std::string::npos);
  const std::string vtp = slurp(out / "wear_surface.vtp");
  for (const char* a : {"wear_depth_mm", "von_mises_max_MPa", "plastic_strain"}) {
    CHECK_MESSAGE(vtp.find(a) != std::string::npos, a);
  }
}

TEST_CASE("kneesim compare --set insert=deformable tabulates stresses per material") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path out = tmp.path / "cmp";
  std::vector<std::string> args = {"compare", "--out", out.string(), "--quiet", "--materials",
                                   "uhmwpe,cfr-peek", "--cycles", "500000", "--update-every",
                                   "500000"};
  args.insert(args.end(), kCoarse.begin(), kCoarse.end());
  const Result r = run_kneesim(args, tmp.path);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  MESSAGE("kneesim compare, deformable, 2 materials, 0.5 Mc / 1 update, coarse: " << r.seconds
                                                                                    << " s wall");
  const Csv csv = read_csv(out / "comparison.csv");
  REQUIRE(csv.rows.size() == 2);
  const int peak = csv.column("mean_peak_pressure_MPa"), vm = csv.column("von_mises_max_surface_MPa");
  REQUIRE(peak >= 0);
  REQUIRE(vm >= 0);
  for (const char* c : {"von_mises_max_subsurface_MPa", "plastic_strain_max_surface",
                        "plastic_strain_max_subsurface", "contact_area_mm2"}) {
    CHECK_MESSAGE(csv.column(c) >= 0, c);
  }
  // CFR-PEEK (E 18 GPa) against UHMWPE (E 0.69 GPa, yield 17 MPa): more pressure
  CHECK(std::stod(csv.rows[1][peak]) > std::stod(csv.rows[0][peak]));
  const std::string md = slurp(out / "comparison.md");
  CHECK(md.find("von Mises") != std::string::npos);
  CHECK(fs::exists(out / "uhmwpe" / "insert_stress.vtu"));
  CHECK(fs::exists(out / "cfr-peek" / "wear_surface.vtp"));
  for (const char* m : {"uhmwpe", "cfr-peek"}) {
    const auto s = nlohmann::json::parse(slurp(out / m / "summary.json"));
    REQUIRE_MESSAGE(s.contains("kinetic_to_internal_max"), m);
    CHECK_MESSAGE(s["kinetic_to_internal_max"].get<double>() > 0.0, m);
  }
}
