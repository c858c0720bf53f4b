// `kneesim run --export-fe` (analysis/run/fe_export.h): the deformable insert's contact problem
// at heel strike and the two load peaks, for the CalculiX cross-check
// (tools/scripts/ccx_crosscheck.py; the cross-check itself is tests/ccx/ccx_crosscheck_long.cpp).
// References: the shipped gait's axial-force key points (physics.md section 3: peaks of 2600 N at
// 13 % and 2200 N at 45 %), the same step's row of kinematics.csv (the frames and the export
// use the same sampling rule), and invariants of the export itself (a rotation, the medial and
// lateral forces as sums of node pressure times tributary area).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/cli_wear/cli_helpers.h"  // find_kneesim, run_kneesim, TempDir, slurp, split

namespace fs = std::filesystem;
using namespace kneesim::test;

namespace {

// the kinematics.csv row whose gait_pct is nearest to pct, by column name
std::map<std::string, double> row_near(const fs::path& csv, double pct) {
  std::istringstream in(slurp(csv));
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> names = split(line, ',');
  std::map<std::string, double> best;
  double best_gap = INFINITY;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split(line, ',');
    const double gap = std::abs(std::stod(cells[0]) - pct);
    if (gap >= best_gap) continue;
    best_gap = gap;
    for (size_t i = 0; i < names.size(); ++i) best[names[i]] = std::stod(cells[i]);
  }
  return best;
}

}  // namespace

TEST_CASE("kneesim run --export-fe writes the insert problem at heel strike and the load peaks") {
  TempDir tmp;
  const fs::path out = tmp.path / "result";
  const Result r = run_kneesim(
      {"run", "--out", out.string(), "--quiet", "--no-plots", "--cycles", "2", "--set",
       "insert=deformable", "--set", "deformable.element_size_mm=3", "--set",
       "deformable.layers=3", "--set", "implant.edge_length_mm=2", "--set", "gait.period_s=0.2",
       "--export-fe"},
      tmp.path);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  const auto e = nlohmann::json::parse(slurp(out / "fe_export.json"));
  const auto summary = nlohmann::json::parse(slurp(out / "summary.json"));

  // the mesh as kneesim integrates it
  const auto& nodes = e["mesh"]["nodes_mm"];
  const auto& elements = e["mesh"]["elements"];
  CHECK(nodes.size() == summary["solid_nodes"].get<size_t>());
  CHECK(elements.size() == summary["solid_elements"].get<size_t>());
  for (const auto& el : elements) {
    REQUIRE(el.size() == 8);
    for (int id : el) REQUIRE((id >= 0 && id < static_cast<int>(nodes.size())));
  }
  const auto& top = e["contact"]["top_nodes"];
  const auto& area = e["contact"]["tributary_area_mm2"];
  REQUIRE(top.size() == summary["solid_surface_nodes"].get<size_t>());
  REQUIRE(area.size() == top.size());
  CHECK(e["contact"]["penalty_N_per_mm"].size() == top.size());
  CHECK(e["mesh"]["top_faces"].size() == e["mesh"]["top_face_element"].size());
  CHECK(e["femur"]["triangles"].size() > 1000);
  CHECK(e["material"]["model"] == "j2");
  CHECK(e["material"]["yield_MPa"].get<double>() == doctest::Approx(17.0));

  // heel strike and the shipped gait's two highest axial-load peaks (13 % and 45 %)
  const auto& instants = e["instants"];
  REQUIRE(instants.size() == 3);
  const double expected[3] = {0.0, 13.0, 45.0};
  const double step_pct = 100.0 * summary["dt_s"].get<double>() / 0.2;
  for (int k = 0; k < 3; ++k) {
    const auto& in = instants[k];
    CAPTURE(k);
    CHECK(in["gait_pct_requested"].get<double>() == doctest::Approx(expected[k]));
    CHECK(std::abs(in["gait_pct"].get<double>() - expected[k]) <= step_pct);
    // X_TF is a rigid transform
    const auto& X = in["X_TF_mm"];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        double dot = 0.0;
        for (int c = 0; c < 3; ++c) dot += X[c][i].get<double>() * X[c][j].get<double>();
        CHECK(dot == doctest::Approx(i == j ? 1.0 : 0.0).epsilon(1e-9));
      }
    // the summary is the node pressures summed: medial z < 0 in T
    const auto& p = in["top_node_pressure_MPa"];
    REQUIRE(p.size() == top.size());
    double medial = 0.0, lateral = 0.0, peak = 0.0, contact_area = 0.0;
    for (size_t i = 0; i < top.size(); ++i) {
      const double pi = p[i].get<double>(), ai = area[i].get<double>();
      if (!(pi > 0.0)) continue;
      (nodes[top[i].get<int>()][2].get<double>() < 0.0 ? medial : lateral) += pi * ai;
      peak = std::max(peak, pi);
      contact_area += ai;
    }
    const auto& s = in["summary"];
    CHECK(medial == doctest::Approx(s["medial_force_N"].get<double>()).epsilon(1e-9));
    CHECK(lateral == doctest::Approx(s["lateral_force_N"].get<double>()).epsilon(1e-9));
    CHECK(peak == doctest::Approx(s["peak_pressure_MPa"].get<double>()).epsilon(1e-12));
    CHECK(contact_area == doctest::Approx(s["contact_area_mm2"].get<double>()).epsilon(1e-9));
    CHECK(in["element_von_mises_MPa"].size() == elements.size());
    CHECK(in["node_position_mm"].size() == nodes.size());
    // the frame of kinematics.csv at that gait % is the same step
    const auto row = row_near(out / "kinematics.csv", expected[k]);
    CHECK(row.at("peak_pressure_MPa") == doctest::Approx(s["peak_pressure_MPa"].get<double>()));
    CHECK(row.at("medial_force_N") == doctest::Approx(s["medial_force_N"].get<double>()));
    CHECK(row.at("axial_force_N") == doctest::Approx(in["applied_axial_force_N"].get<double>()));
  }
  // the load peaks carry load; heel strike (after a cycle) touches
  CHECK(instants[1]["summary"]["peak_pressure_MPa"].get<double>() > 5.0);
  CHECK(instants[2]["summary"]["peak_pressure_MPa"].get<double>() > 5.0);
  CHECK(instants[0]["summary"]["nodes_in_contact"].get<int>() > 0);
}

TEST_CASE("--export-fe-pcts chooses the instants; bad export requests exit 2 in one line") {
  TempDir tmp;
  const fs::path out = tmp.path / "result";
  const Result r = run_kneesim(
      {"run", "--out", out.string(), "--quiet", "--no-plots", "--cycles", "1", "--set",
       "insert=deformable", "--set", "deformable.element_size_mm=3", "--set",
       "deformable.layers=3", "--set", "implant.edge_length_mm=2", "--set", "gait.period_s=0.2",
       "--export-fe-pcts", "30,20.5"},
      tmp.path);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  const auto e = nlohmann::json::parse(slurp(out / "fe_export.json"));
  REQUIRE(e["instants"].size() == 2);
  CHECK(e["instants"][0]["gait_pct_requested"].get<double>() == doctest::Approx(20.5));
  CHECK(e["instants"][1]["gait_pct_requested"].get<double>() == doctest::Approx(30.0));

  struct Case {
    std::vector<std::string> args;
    std::vector<std::string> mentions;
  };
  const std::vector<Case> cases = {
      {{"--export-fe"}, {"deformable"}},  // the rigid insert has no hex mesh to export
      {{"--set", "insert=deformable", "--export-fe-pcts", "100"}, {"--export-fe-pcts", "100"}},
  };
  for (const Case& c : cases) {
    const fs::path bad = tmp.path / "bad";
    std::vector<std::string> args = {"run", "--out", bad.string(), "--quiet", "--no-plots",
                                     "--set", "implant.edge_length_mm=2"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const Result b = run_kneesim(args, tmp.path);
    INFO("stderr: " << b.err);
    CHECK(b.exit_code == 2);
    CHECK(count_lines(b.err) == 1);
    for (const auto& m : c.mentions) CHECK_MESSAGE(b.err.find(m) != std::string::npos, m);
    CHECK_FALSE(fs::exists(bad / "fe_export.json"));
    CHECK_FALSE(fs::exists(bad / "summary.json"));
  }
}
