// A wear update whose figures are not finite, or whose two volumes (enclosed-volume loss of the
// closed insert and depth integral) disagree beyond kVolumeBookkeepingTolerance, is refused by
// wear::check_update_record, so the loop stops with a status instead of ending "complete"
// (issue 15: a 1e30 vertex gave nan mm^3 and a bookkeeping difference of 5.8e27 with exit 0).
// Reference: the stated bound, 10 % (wear/wear_loop.h: deep scars legitimately reach 2.5 %).
#include <doctest/doctest.h>

#include <cmath>

#include "analysis/run/gait_run.h"
#include "wear/wear_loop.h"

using kneesim::wear::check_update_record;
using kneesim::wear::UpdateRecord;

namespace {
UpdateRecord consistent_record() {
  UpdateRecord r;
  r.cycles = 250000;
  r.volume = 3.50e-9;
  r.volume_depth = 3.49e-9;  // 0.29 %
  r.max_depth = 2e-5;
  r.peak_pressure = 30e6;
  return r;
}
}  // namespace

TEST_CASE("finite records within the bookkeeping tolerance pass") {
  CHECK(check_update_record(consistent_record(), true).empty());
  UpdateRecord unworn;  // cycle 0: nothing to compare
  CHECK(check_update_record(unworn, true).empty());
}

TEST_CASE("a non-finite figure is named with the cycles") {
  UpdateRecord r = consistent_record();
  r.volume = NAN;
  CHECK(check_update_record(r, true) ==
        "after 250000 cycles the volume of the update is not a finite number");
  r = consistent_record();
  r.ie_rom = INFINITY;
  CHECK(check_update_record(r, false).find("ie_rom") != std::string::npos);
}

TEST_CASE("volume bookkeeping beyond 10 % fails a closed insert only") {
  UpdateRecord r = consistent_record();
  r.volume = r.volume_depth * 1.101;
  const std::string why = check_update_record(r, true);
  CAPTURE(why);
  CHECK(why.find("differ by 10.1 % (allowed 10 %)") != std::string::npos);
  // an open insert has no enclosed volume to compare
  CHECK(check_update_record(r, false).empty());
  r.volume = r.volume_depth * 0.91;
  CHECK(check_update_record(r, true).empty());
  r.volume = r.volume_depth * 0.899;
  CHECK_FALSE(check_update_record(r, true).empty());
}

TEST_CASE("a gait run's table with a non-finite cell is found, naming column and row") {
  // kneesim run ends as failed (summary.failed.json, exit 1) on such a table instead of
  // writing summary.json (analysis/run/gait_run.cpp)
  kneesim::io::Table t;
  t.columns = {"gait_pct", "ap_mm"};
  t.add_row({0.0, 1.0});
  t.add_row({1.0, 2.0});
  CHECK(kneesim::run::find_non_finite(t).empty());
  t.add_row({2.0, NAN});
  CHECK(kneesim::run::find_non_finite(t) == "ap_mm = nan in row 3 of kinematics.csv");
  t.rows[0][0] = INFINITY;
  CHECK(kneesim::run::find_non_finite(t) == "gait_pct = inf in row 1 of kinematics.csv");
}
