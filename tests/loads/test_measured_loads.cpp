// Measured load tables (loads/iso14243/measured_loads.h): unit conversion and resampling of one
// cycle against closed forms, and the bad-input contract of issue 16 (one sentence naming the
// file, row and column) for missing columns, non-monotonic time, fewer than one gait cycle,
// unknown force units and a window outside the data.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>

#include "loads/iso14243/measured_loads.h"
#include "tests/loads/input_error.h"
#include "tests/loads/temp_dir.h"

using namespace kneesim;
using kneesim::test::input_error_message;

namespace {

constexpr double kLbf = 4.4482216152605;

// two cycles of 1.2 s at 100 Hz from t = 0.5 s: load cells A and B in lbf (bare headers),
// flexion in deg; total = 100 + 50 sin(2 pi (t - 0.5) / 1.2) lbf
std::string table(bool trailing_comma = false) {
  std::ostringstream o;
  o << "Time(sec),A,B,GON\n";
  for (int i = 0; i <= 240; ++i) {
    const double t = 0.5 + 0.01 * i;
    const double total = 100.0 + 50.0 * std::sin(2.0 * std::numbers::pi * (t - 0.5) / 1.2);
    o << t << "," << 0.7 * total << "," << 0.3 * total << "," << 10.0 + 5.0 * i / 240.0
      << (trailing_comma ? ",\n" : "\n");
  }
  return o.str();
}

loads::MeasuredLoadSpec spec(const std::filesystem::path& file) {
  loads::MeasuredLoadSpec s;
  s.file = file;
  s.origin = "test.toml [gait.measured]";
  s.time_column = "Time(sec)";
  s.window = {0.5, 1.7};
  s.units = {{"force", "lbf"}, {"angle", "deg"}};
  s.channels = {"axial_force_N = A + B", "flexion_deg = GON", "medial_force_N = 1.0 * A"};
  return s;
}

}  // namespace

TEST_CASE("a measured table becomes one periodic gait cycle in the channels' units") {
  test::TempDir tmp;
  for (bool trailing : {false, true}) {  // spreadsheet exports end rows with a comma
    const auto loads = loads::read_measured_loads(spec(tmp.write("t.csv", table(trailing))));
    CHECK_FALSE(loads.percent);
    REQUIRE(loads.names.size() == 3);
    const auto w = loads::cycle_waveform(loads, {"axial_force_N", "flexion_deg"});
    REQUIRE(w.channel_count() == 2);
    // closed form: total at 25 % of the window is 150 lbf (sine peak), at 75 % 50 lbf
    const int ax = w.channel("axial_force_N");
    CHECK(w.value(ax, 25.0) == doctest::Approx(150.0 * kLbf).epsilon(1e-3));
    CHECK(w.value(ax, 75.0) == doctest::Approx(50.0 * kLbf).epsilon(1e-3));
    // periodic: the flexion ramp's drift over the cycle (2.5 deg) is removed linearly
    const int fe = w.channel("flexion_deg");
    CHECK(w.value(fe, 0.0) == doctest::Approx(10.0).epsilon(1e-6));
    CHECK(w.value(fe, 100.0) == doctest::Approx(10.0).epsilon(1e-6));
    CHECK(w.value(fe, 50.0) == doctest::Approx(10.0).epsilon(1e-3));
    // a compare channel keeps its weights: medial = 0.7 total
    const int med = loads.channel("medial_force_N");
    CHECK(loads.values[med][60] == doctest::Approx(0.7 * loads.values[0][60]));
  }
}

TEST_CASE("units come from the header when it has them") {
  test::TempDir tmp;
  const auto f = tmp.write("u.csv",
                           "time_s,total(kN),flex[rad]\n0,1,0\n0.25,1,0.1\n0.5,2,0.2\n0.75,1,0.1\n"
                           "1,1,0\n1.25,1,0\n1.5,1,0\n1.75,1,0\n2,1,0\n");
  loads::MeasuredLoadSpec s;
  s.file = f;
  s.window = {0.0, 1.0};
  s.channels = {"axial_force_N = total", "flexion_deg = flex"};
  const auto loads = loads::read_measured_loads(s);
  CHECK(loads.values[0][2] == doctest::Approx(2000.0));
  CHECK(loads.values[1][2] == doctest::Approx(0.2 * 180.0 / std::numbers::pi));
}

TEST_CASE("bad measured tables are refused with file, row and column") {
  test::TempDir tmp;
  const auto good = tmp.write("good.csv", table());
  auto message = [&](loads::MeasuredLoadSpec s) {
    return input_error_message([&] { loads::read_measured_loads(s); });
  };
  auto names = [](const std::string& m, const std::string& file, const std::string& row,
                  const std::string& column) {
    INFO(m);
    CHECK(m.find(file) != std::string::npos);
    CHECK(m.find(row) != std::string::npos);
    CHECK(m.find("column '" + column + "'") != std::string::npos);
  };
  SUBCASE("missing column") {
    auto s = spec(good);
    s.channels = {"axial_force_N = A + C"};
    names(message(s), "good.csv", "row 1", "C");
  }
  SUBCASE("non-monotonic time") {
    std::string text = table();
    const auto at = text.find("\n0.53,");
    REQUIRE(at != std::string::npos);
    text.replace(at, 6, "\n0.51,");  // row 5 (0.53 s) now repeats 0.51 s
    const auto m = message(spec(tmp.write("mono.csv", text)));
    names(m, "mono.csv", "row 5", "Time(sec)");
    CHECK(m.find("does not increase") != std::string::npos);
  }
  SUBCASE("fewer than one gait cycle") {
    auto s = spec(good);
    s.window = {0.5, 3.5};  // 3 s cycle, 2.4 s of data
    const auto m = message(s);
    names(m, "good.csv", "rows 2-242", "Time(sec)");
    CHECK(m.find("fewer than one full gait cycle") != std::string::npos);
  }
  SUBCASE("forces in unknown units") {
    auto s = spec(good);
    s.units.erase("force");
    auto m = message(s);
    names(m, "good.csv", "row 1", "A");
    CHECK(m.find("unknown units") != std::string::npos);
    const auto f = tmp.write("lbs.csv", "t(s),A(lbs)\n0,1\n0.1,1\n0.2,1\n0.3,1\n0.4,1\n0.5,1\n0.6,1\n0.7,1\n");
    s = loads::MeasuredLoadSpec{};
    s.file = f;
    s.channels = {"axial_force_N = A"};
    m = message(s);
    names(m, "lbs.csv", "row 1", "A(lbs)");
    CHECK(m.find("'lbs'") != std::string::npos);
  }
  SUBCASE("window outside the data") {
    auto s = spec(good);
    s.window = {2.0, 3.0};
    const auto m = message(s);
    names(m, "good.csv", "rows 2-242", "Time(sec)");
    CHECK(m.find("outside the data") != std::string::npos);
  }
  SUBCASE("gait percent covering less than a cycle") {
    const auto f = tmp.write("pct.csv", "gait_pct,F(N)\n0,1\n10,1\n20,1\n30,1\n40,1\n50,1\n60,1\n70,1\n80,1\n");
    loads::MeasuredLoadSpec s;
    s.file = f;
    s.channels = {"axial_force_N = F"};
    const auto m = message(s);
    names(m, "pct.csv", "rows 2-10", "gait_pct");
    CHECK(m.find("fewer than one full gait cycle") != std::string::npos);
  }
}

TEST_CASE("the Grand Challenge JW table: total force as the data README gives it") {
  const char* env = std::getenv("KNEESIM_DATA");
  const std::filesystem::path file =
      std::filesystem::path(env ? env : "../shared/data") / "gc4_jw/ngait_og3_knee_forces.csv";
  if (!std::filesystem::exists(file)) {
    MESSAGE("skipped: " << file << " not found (set KNEESIM_DATA)");
    return;
  }
  loads::MeasuredLoadSpec s;
  s.file = file;
  s.time_column = "Time(sec)";
  s.units = {{"force", "lbf"}, {"angle", "deg"}};
  s.channels = {"axial_force_N = PM + AM + AL + PL", "flexion_deg = GON"};
  const auto loads = loads::read_measured_loads(s);
  // data README: peak 1601 N at 2.58 s, GON 2.8-64.7 deg, 1.807-4.223 s
  double peak = 0.0, t_peak = 0.0, fmin = 1e9, fmax = -1e9;
  for (size_t i = 0; i < loads.time.size(); ++i) {
    if (loads.values[0][i] > peak) peak = loads.values[0][i], t_peak = loads.time[i];
    fmin = std::min(fmin, loads.values[1][i]);
    fmax = std::max(fmax, loads.values[1][i]);
  }
  CHECK(peak == doctest::Approx(1601.0).epsilon(1e-3));
  CHECK(t_peak == doctest::Approx(2.58).epsilon(0.005));
  CHECK(fmin == doctest::Approx(2.8).epsilon(0.02));
  CHECK(fmax == doctest::Approx(64.7).epsilon(0.01));
  CHECK(loads.time.front() == doctest::Approx(1.807).epsilon(1e-3));
  CHECK(loads.time.back() == doctest::Approx(4.223).epsilon(1e-3));
}
