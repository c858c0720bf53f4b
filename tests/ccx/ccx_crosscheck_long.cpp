// The independent FE cross-check: kneesim's deformable insert against CalculiX on kneesim's own
// hex mesh, at heel strike and the two axial-load peaks of the default run, linear elastic and
// J2 (tools/scripts/ccx_crosscheck.py; the method and the table: docs/validation.md,
// "Deformable insert against CalculiX"). Reference: CalculiX's static solution with the femur
// rigid at kneesim's pose and loaded with kneesim's axial contact force (same axial load).
// Acceptance: kneesim's peak and mean pressure and contact area within 10 % of it at every
// instant, or the stated reason why not: kneesim's penalty (the surface element's own
// stiffness) is softer than CalculiX's near-hard contact, which shows as a larger area and a
// lower peak and mean pressure in kneesim, and disappears when CalculiX is given kneesim's penalty
// (then the two codes solve the same problem and must agree within 5 % on peak pressure and
// normal force, and on the contact area up to two patch-edge nodes whose gap is within
// round-off of zero: what is left is the element formulation, explicit against static, and the
// pressure recovery).
// The 2 mm insert, not the default 1 mm one: one CalculiX instant on the 1 mm mesh takes about
// 40 min on a 2-core machine. Takes about an hour; skipped, saying why, without ccx.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/cli_wear/cli_helpers.h"  // find_kneesim, TempDir, slurp

namespace fs = std::filesystem;
using namespace kneesim::test;

namespace {

double pct_diff(const nlohmann::json& row, const std::string& quantity) {
  const double k = row["kneesim_" + quantity].get<double>();
  const double c = row["ccx_" + quantity].get<double>();
  return 100.0 * (k - c) / c;
}

int run_script(const std::string& args, const fs::path& log) {
  const char* source = std::getenv("KNEESIM_SOURCE_DIR");
  REQUIRE_MESSAGE(source != nullptr, "KNEESIM_SOURCE_DIR is set by ctest");
  const std::string cmd = "/usr/bin/python3 " +
                          (fs::path(source) / "tools/scripts/ccx_crosscheck.py").string() + " " +
                          args + " > " + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  INFO(slurp(log));
  REQUIRE(WIFEXITED(status));
  return WEXITSTATUS(status);
}

}  // namespace

TEST_CASE("CalculiX cross-check: pressure and area within 10 % at three instants, or the penalty") {
  if (std::system("command -v ccx > /dev/null 2>&1") != 0) {
    MESSAGE("skipped: CalculiX (ccx) is not on PATH; tools/scripts/setup.sh installs calculix-ccx");
    return;
  }
  const fs::path kneesim = find_kneesim();
  REQUIRE_MESSAGE(!kneesim.empty(), "build kneesim first");
  TempDir tmp;
  const fs::path out = tmp.path / "crosscheck";
  const fs::path soft = tmp.path / "crosscheck_kneesim_penalty";
  // 0: every figure ran; 1: ccx or kneesim failed (the log names it)
  REQUIRE(run_script("--out " + out.string() + " --kneesim " + kneesim.string() +
                         " --set deformable.element_size_mm=2",
                     tmp.path / "log.txt") == 0);
  MESSAGE(slurp(out / "crosscheck.md"));
  REQUIRE(run_script("--out " + soft.string() + " --export " +
                         (out / "kneesim_elastic" / "fe_export.json").string() +
                         " --penalty-factor 1",
                     tmp.path / "log_soft.txt") == 0);
  MESSAGE(slurp(soft / "crosscheck.md"));
  const auto hard = nlohmann::json::parse(slurp(out / "crosscheck.json"))["rows"];
  const auto same = nlohmann::json::parse(slurp(soft / "crosscheck.json"))["rows"];
  // every instant compared: 2 material models x 3 instants x 2 boundary conditions
  REQUIRE(hard.size() == 12);
  REQUIRE(same.size() == 6);

  // CalculiX with kneesim's penalty, same axial load: the two codes agree within 5 %
  std::map<long, nlohmann::json> same_penalty;  // gait % -> row
  for (const auto& r : same) {
    if (r["bc"] != "same axial load") continue;
    const long pct = std::lround(r["gait_pct"].get<double>());
    same_penalty[pct] = r;
    INFO("penalty as kneesim's, gait % " << pct);
    CHECK(std::abs(pct_diff(r, "peak_pressure_MPa")) < 5.0);
    // the area is a count of nodes with a positive pressure times their tributary areas: a
    // patch edge node whose gap is within round-off of zero is in contact in one code and not
    // in the other, and on the 2 mm mesh one such node of a 12-node heel-strike patch is 9 %
    // of the area. So: at most two nodes' difference, the area difference equal to those
    // nodes' tributary areas (the patch's mean per node) within 5 % of the area, and the same
    // normal force (mean pressure x area) within 5 %
    const double nodes_k = r["kneesim_nodes_in_contact"].get<double>();
    const double nodes_c = r["ccx_nodes_in_contact"].get<double>();
    const double area_k = r["kneesim_contact_area_mm2"].get<double>();
    const double area_c = r["ccx_contact_area_mm2"].get<double>();
    CHECK(std::abs(nodes_k - nodes_c) <= 2.0);
    const double edge_nodes_area = (nodes_k - nodes_c) * area_c / nodes_c;
    CHECK(std::abs(area_k - area_c - edge_nodes_area) < 0.05 * area_c);
    const double force_k = r["kneesim_mean_pressure_MPa"].get<double>() * area_k;
    const double force_c = r["ccx_mean_pressure_MPa"].get<double>() * area_c;
    CHECK(std::abs(force_k - force_c) < 0.05 * force_c);
  }
  REQUIRE(same_penalty.size() == 3);

  for (const auto& r : hard) {
    if (r["bc"] != "same axial load") continue;
    const long pct = std::lround(r["gait_pct"].get<double>());
    INFO(r["model"].get<std::string>() << ", gait % " << pct);
    // CalculiX in equilibrium with the load it was given
    CHECK(r["ccx_axial_force_N"].get<double>() ==
          doctest::Approx(r["kneesim_axial_force_N"].get<double>()).epsilon(0.005));
    // the nodal pressures times kneesim's tributary areas carry the rigid body's load: their
    // sum (normal force magnitudes) is the axial force over the mean cosine of the normals'
    // tilt, 1 to 1.06 for the dishes' slopes; a wrong area or pressure would be off by more
    const double ratio =
        r["ccx_contact_force_sum_N"].get<double>() / r["ccx_axial_force_N"].get<double>();
    CHECK(ratio > 0.98);
    CHECK(ratio < 1.06);
    const double peak = pct_diff(r, "peak_pressure_MPa");
    const double mean = pct_diff(r, "mean_pressure_MPa");
    const double area = pct_diff(r, "contact_area_mm2");
    if (std::abs(peak) < 10.0 && std::abs(mean) < 10.0 && std::abs(area) < 10.0) continue;
    // beyond 10 %: only with the signature of kneesim's softer penalty (area not smaller, peak
    // and mean pressure lower), at an instant where the same penalty in CalculiX removes it
    // (checked above)
    CHECK(area >= 0.0);
    CHECK(peak < 0.0);
    CHECK(mean < 0.0);
    CHECK(same_penalty.count(pct) == 1);
  }
}
