// Every rig preset end to end through `kneesim run`, `kneesim wear` and `kneesim compare`
// (issue 14 item 1), on the coarse built-in implant (2 mm edges), one geometry update.
// References:
//  - joint kinematics are the tibia relative to the femur (engine/joint_coordinates.h), so the
//    joint AP stays on the insert: |ap_mm| < half the insert's AP depth (46 / 2 = 23 mm) in
//    every row;
//  - plausible loads: the restraint's AP force never exceeds the applied AP force's largest
//    magnitude by more than 10 % (the springs can at most take the whole AP force plus what
//    the joint's geometry pushes back; 385 N against 265 N was the materials_study preset's
//    symptom of a rig whose AP had nothing to hold it);
//  - materials_study: kneesim frees each joint DOF on one carriage (the femur's AP, the tibia's
//    AP locked); the study's literal rig also frees the tibial AP against its springs
//    (four of 10.4 N/mm: 41.6 N/mm). CVODE integrates that literal rig (the explicit step
//    refuses a DOF moved on both carriages): its joint AP and IE ranges are the preset's within
//    5 % (the femur free in AP carries no AP force, so the springs take the whole AP force and
//    the joint follows the contact alone; measured 13.39 / 7.84 against the preset's CVODE
//    13.45 / 7.85 on default edges), its restraint force equals the applied AP force within
//    10 % and its tibial carriage travels less than 10 mm (F_AP / k = 265 N / 41.6 N/mm =
//    6.4 mm; the insert is 46 mm deep);
//  - force-controlled presets: a range of motion within half the smallest and twice the largest
//    published force-controlled figure (AP: materials study predicted 6.7 mm, Pal 2008 99th
//    percentile 12.34 mm -> 3.35-24.7 mm; IE: Pal 2008 1st percentile 7.66 deg, Pal 99th
//    percentile 13.85 deg -> 3.8-27.7 deg). The implants differ (NexGen CR, Genesis II, the
//    generic one here), hence the factor of two: this is a plausibility band, catching runaway
//    or locked rigs, not a validation;
//  - displacement preset: AP and IE are prescribed on the tibial carriage, whose pivot is 5 mm
//    medial of the insert centre, so the joint AP (at the insert centre) is the prescribed AP
//    plus 5 mm sin(IE): closed form from the shipped ISO 14243-3-shaped waveform, AP from 0 mm
//    at IE -1 deg (0 %) to -5 mm at IE +5 deg (58 %): range 5 - 5 (sin 5 + sin 1 deg) =
//    4.477 mm; IE range 6 deg exactly;
//  - settled figures under the plain names (item 7): the AP/IE ranges in wear's summary.json,
//    its wear.csv row 0 and compare's comparison.csv are those of `kneesim run` (the same
//    settled cycle on the pristine insert), within 1e-4 relative (not bit for bit: the wear
//    loop starts a cycle with a fresh contact-sleeping schedule, which moves round-off).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>

#include "tests/cli_wear/cli_helpers.h"

using namespace kneesim::test;

namespace {

struct Csv {
  std::map<std::string, size_t> col;
  std::vector<std::vector<double>> rows;  // non-numeric cells as NaN
  std::vector<std::vector<std::string>> text;
  double at(size_t row, const std::string& c) const { return rows.at(row).at(col.at(c)); }
};

Csv read_csv(const fs::path& p) {
  Csv t;
  std::istringstream in(slurp(p));
  std::string line;
  std::getline(in, line);
  const auto header = split(line, ',');
  for (size_t i = 0; i < header.size(); ++i) t.col[header[i]] = i;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    t.text.push_back(split(line, ','));
    std::vector<double> v;
    for (const auto& cell : t.text.back()) {
      char* end = nullptr;
      const double x = std::strtod(cell.c_str(), &end);
      v.push_back(end != cell.c_str() ? x : NAN);
    }
    t.rows.push_back(v);
  }
  return t;
}

const std::vector<std::string> kCoarse = {"--set", "implant.edge_length_mm=2"};

std::vector<std::string> with(std::vector<std::string> a, const std::string& preset) {
  a.insert(a.end(), kCoarse.begin(), kCoarse.end());
  a.insert(a.end(), {"--set", "rig.preset=" + preset});
  return a;
}

}  // namespace

TEST_CASE("every rig preset runs end to end in run, wear and compare") {
  REQUIRE(!find_kneesim().empty());
  constexpr double kDeg = std::numbers::pi / 180.0;
  for (const std::string preset : {"stanmore", "materials_study", "iso", "displacement"}) {
    CAPTURE(preset);
    TempDir tmp;
    const fs::path run_dir = tmp.path / "run", wear_dir = tmp.path / "wear",
                   cmp_dir = tmp.path / "cmp";

    // kneesim run
    const Result run = run_kneesim(with({"run", "--quiet", "--out", run_dir.string()}, preset),
                                   tmp.path, "run");
    INFO("run stderr: " << run.err);
    REQUIRE(run.exit_code == 0);
    const auto rs = nlohmann::json::parse(slurp(run_dir / "summary.json"));
    const double ap_rom = rs["ap_rom_mm"].get<double>(), ie_rom = rs["ie_rom_deg"].get<double>();
    const Csv kin = read_csv(run_dir / "kinematics.csv");
    REQUIRE(kin.rows.size() == 100);
    double max_abs_ap = 0.0;
    for (size_t i = 0; i < kin.rows.size(); ++i) {
      max_abs_ap = std::max(max_abs_ap, std::abs(kin.at(i, "ap_mm")));
    }
    MESSAGE(preset << ": AP range " << ap_rom << " mm, IE range " << ie_rom
                   << " deg, max |AP| " << max_abs_ap << " mm, medial share "
                   << rs["medial_fraction_stance"].get<double>());
    CHECK(max_abs_ap < 23.0);
    double max_applied = 0.0, max_restraint = 0.0;
    for (size_t i = 0; i < kin.rows.size(); ++i) {
      max_applied = std::max(max_applied, std::abs(kin.at(i, "ap_force_N")));
      max_restraint = std::max(max_restraint, std::abs(kin.at(i, "restraint_force_N")));
    }
    MESSAGE(preset << ": largest applied AP force " << max_applied << " N, restraint "
                   << max_restraint << " N");
    CHECK(max_restraint <= 1.1 * max_applied + 1e-9);
    if (preset == "displacement") {
      CHECK(ap_rom == doctest::Approx(5.0 - 5.0 * (std::sin(5 * kDeg) + std::sin(1 * kDeg)))
                          .epsilon(0.002));
      CHECK(ie_rom == doctest::Approx(6.0).epsilon(0.002));
    } else {
      CHECK(ap_rom > 3.35);
      CHECK(ap_rom < 24.7);
      CHECK(ie_rom > 3.8);
      CHECK(ie_rom < 27.7);
    }

    // kneesim wear: one update; row 0 and the summary carry the run's settled figures
    const Result wear = run_kneesim(
        with({"wear", "--quiet", "--cycles", "250000", "--update-every", "250000", "--out",
              wear_dir.string()},
             preset),
        tmp.path, "wear");
    INFO("wear stderr: " << wear.err);
    REQUIRE(wear.exit_code == 0);
    const auto ws = nlohmann::json::parse(slurp(wear_dir / "summary.json"));
    CHECK(ws["volume_mm3"].get<double>() > 0.0);
    CHECK(ws["ap_rom_mm"].get<double>() == doctest::Approx(ap_rom).epsilon(1e-4));
    CHECK(ws["ie_rom_deg"].get<double>() == doctest::Approx(ie_rom).epsilon(1e-4));
    const Csv wcsv = read_csv(wear_dir / "wear.csv");
    REQUIRE(wcsv.rows.size() == 2);
    CHECK(wcsv.at(0, "cycles") == 0.0);
    CHECK(wcsv.at(0, "ap_rom_mm") == doctest::Approx(ap_rom).epsilon(1e-4));

    // kneesim compare: two materials, the UHMWPE row is the wear run's
    const Result cmp = run_kneesim(
        with({"compare", "--quiet", "--no-break-even", "--materials", "uhmwpe,peek", "--cycles",
              "250000", "--update-every", "250000", "--out", cmp_dir.string()},
             preset),
        tmp.path, "cmp");
    INFO("compare stderr: " << cmp.err);
    REQUIRE(cmp.exit_code == 0);
    const Csv c = read_csv(cmp_dir / "comparison.csv");
    REQUIRE(c.rows.size() == 2);
    for (size_t i = 0; i < c.rows.size(); ++i) {
      if (c.text[i][c.col.at("material")] != "uhmwpe") continue;
      CHECK(c.at(i, "ap_rom_mm") == doctest::Approx(ap_rom).epsilon(1e-4));
      CHECK(c.at(i, "volume_mm3") ==
            doctest::Approx(ws["volume_mm3"].get<double>()).epsilon(1e-6));
    }
  }
}

TEST_CASE("materials_study: the study's literal rig (both AP carriages free) gives the preset's joint ranges") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  auto run = [&](const std::string& name, std::vector<std::string> extra) {
    std::vector<std::string> args =
        with({"run", "--quiet", "--no-plots", "--set", "solver.integrator=cvode", "--out",
              (tmp.path / name).string()},
             "materials_study");
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = run_kneesim(args, tmp.path, name);
    INFO(name << " stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(slurp(tmp.path / name / "summary.json"));
  };
  const auto preset = run("preset", {});
  const auto literal = run("literal", {"--set", "rig.tibia.ap=force"});
  const double ap = literal["ap_rom_mm"].get<double>(), ie = literal["ie_rom_deg"].get<double>();
  MESSAGE("literal rig (CVODE): AP " << ap << " mm, IE " << ie << " deg; preset (CVODE): AP "
                                     << preset["ap_rom_mm"].get<double>() << " mm, IE "
                                     << preset["ie_rom_deg"].get<double>() << " deg");
  CHECK(ap == doctest::Approx(preset["ap_rom_mm"].get<double>()).epsilon(0.05));
  CHECK(ie == doctest::Approx(preset["ie_rom_deg"].get<double>()).epsilon(0.05));
  const Csv kin = read_csv(tmp.path / "literal" / "kinematics.csv");
  double lo = 0.0, hi = 0.0, max_applied = 0.0, max_restraint = 0.0;
  const double k_N_per_mm = 4.0 * 10.4;
  for (size_t i = 0; i < kin.rows.size(); ++i) {
    const double f = kin.at(i, "restraint_force_N");
    lo = std::min(lo, -f / k_N_per_mm);  // tibial carriage travel x = -F / k [mm]
    hi = std::max(hi, -f / k_N_per_mm);
    max_applied = std::max(max_applied, std::abs(kin.at(i, "ap_force_N")));
    max_restraint = std::max(max_restraint, std::abs(f));
  }
  MESSAGE("literal rig: tibial carriage travel " << lo << " .. " << hi << " mm, restraint "
                                                 << max_restraint << " N, applied "
                                                 << max_applied << " N");
  CHECK(max_restraint == doctest::Approx(max_applied).epsilon(0.1));
  CHECK(hi - lo < 10.0);
}
