// Every rig preset end to end through `kneesim run`, `kneesim wear` and `kneesim compare`
// (issue 14 item 1), on the coarse built-in implant (2 mm edges), one geometry update.
// References:
//  - joint kinematics are the tibia relative to the femur (engine/joint_coordinates.h), so the
//    joint AP stays on the insert: |ap_mm| < half the insert's AP depth (46 / 2 = 23 mm) in
//    every row (with the femoral AP free the tibial carriage itself travels about 25 mm, the
//    AP force over the 10.4 N/mm restraint, which the old carriage-based output reported);
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
