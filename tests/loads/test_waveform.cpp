// Waveform reader and interpolator. References: the half-cosine formula of physics.md section 3
// (ISO 14243-3 reproduces flexion 8 (1 - cos(pi t / 15)) over 0-15 % and the published axial
// forces at its key points exactly), linear interpolation by hand, periodicity, and the exact
// error sentences.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>

#include "engine/io/source_tree.h"
#include "engine/errors.h"
#include "loads/iso14243/conventions.h"
#include "loads/iso14243/text_table.h"
#include "loads/iso14243/waveform.h"
#include "temp_dir.h"

using kneesim::InputError;
using kneesim::loads::delay_channels;
using kneesim::loads::load_waveform;
using kneesim::loads::Waveform;
using kneesim::test::TempDir;

namespace {

std::filesystem::path source_dir() {
  const char* s = std::getenv("KNEESIM_SOURCE_DIR");
  return s ? std::filesystem::path(s) : kneesim::io::source_dir();
}

Waveform shipped(const char* name) {
  return load_waveform(source_dir() / "loads/iso14243" / name);
}

// the message of the InputError thrown by loading `text`, or "" when none is thrown
std::string load_error(const std::string& text) {
  TempDir dir;
  auto file = dir.write("w.csv", text);
  try {
    load_waveform(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("shipped ISO 14243-1 key points reproduce the published values") {
  Waveform w = shipped("iso14243_1_approx.csv");
  const int axial = w.channel("axial_force_N");
  const int flex = w.channel("flexion_deg");
  REQUIRE(axial >= 0);
  REQUIRE(flex >= 0);
  CHECK(w.channel("ap_force_N") >= 0);
  CHECK(w.channel("ie_torque_Nm") >= 0);
  CHECK(w.channel("nope") == -1);
  // key points are hit exactly
  CHECK(w.value(axial, 13.0) == doctest::Approx(2600.0).epsilon(1e-12));
  CHECK(w.value(axial, 3.0) == doctest::Approx(1887.3).epsilon(1e-12));
  CHECK(w.value(axial, 7.0) == doctest::Approx(1174.6).epsilon(1e-12));
  CHECK(w.value(axial, 0.0) == doctest::Approx(167.6).epsilon(1e-12));
  // flexion over 0-15 % is 8 (1 - cos(pi t / 15)) deg
  for (double t = 0.0; t <= 15.0; t += 0.25) {
    CHECK(std::abs(w.value(flex, t) - 8.0 * (1.0 - std::cos(std::numbers::pi * t / 15.0))) < 1e-9);
  }
  // the derivative of that curve is (8 pi / 15) sin(pi t / 15) per %
  for (double t = 0.5; t < 15.0; t += 0.5) {
    CHECK(std::abs(w.derivative(flex, t) -
                   8.0 * std::numbers::pi / 15.0 * std::sin(std::numbers::pi * t / 15.0)) < 1e-9);
  }
}

TEST_CASE("waveforms are periodic over 100 %") {
  Waveform w = shipped("iso14243_1_approx.csv");
  for (int c = 0; c < w.channel_count(); ++c) {
    for (double p = 0.0; p < 100.0; p += 0.37) {
      const double v = w.value(c, p);
      CHECK(std::abs(w.value(c, p + 100.0) - v) < 1e-9 * (1.0 + std::abs(v)));
      CHECK(std::abs(w.value(c, p - 200.0) - v) < 1e-9 * (1.0 + std::abs(v)));
      CHECK(std::abs(w.derivative(c, p + 300.0) - w.derivative(c, p)) < 1e-6);
    }
  }
}

TEST_CASE("derivative matches a central finite difference") {
  Waveform w = shipped("iso14243_3_approx.csv");
  const double h = 1e-5;
  for (int c = 0; c < w.channel_count(); ++c) {
    for (double p = 0.3; p < 100.0; p += 1.1) {
      const double fd = (w.value(c, p + h) - w.value(c, p - h)) / (2 * h);
      CHECK(std::abs(w.derivative(c, p) - fd) < 1e-4 * (1.0 + std::abs(fd)));
    }
  }
}

TEST_CASE("ISO 14243-3-shaped default has the displacement channels in range") {
  Waveform w = shipped("iso14243_3_approx.csv");
  const int ap = w.channel("ap_mm");
  const int ie = w.channel("ie_deg");
  REQUIRE(ap >= 0);
  REQUIRE(ie >= 0);
  double ap_min = 1e9, ap_max = -1e9, ie_min = 1e9, ie_max = -1e9;
  for (double p = 0.0; p < 100.0; p += 0.1) {
    ap_min = std::min(ap_min, w.value(ap, p));
    ap_max = std::max(ap_max, w.value(ap, p));
    ie_min = std::min(ie_min, w.value(ie, p));
    ie_max = std::max(ie_max, w.value(ie, p));
  }
  CHECK(ap_min == doctest::Approx(-5.0).epsilon(1e-9));
  CHECK(ap_max == doctest::Approx(0.0));
  CHECK(ie_min == doctest::Approx(-1.0).epsilon(1e-9));
  CHECK(ie_max == doctest::Approx(5.0).epsilon(1e-9));
  CHECK(w.value(w.channel("axial_force_N"), 13.0) == doctest::Approx(2600.0));
}

TEST_CASE("table form interpolates linearly and wraps to the first row") {
  TempDir dir;
  auto file = dir.write("t.csv",
                        "# a table\n"
                        "gait_pct,flexion_deg,axial_force_N\n"
                        "10, 0, 100\n"
                        "20, 10, 300\n"
                        "\n"
                        "60, 30, 200\n");
  Waveform w = load_waveform(file);
  CHECK(w.channel_names() == std::vector<std::string>{"flexion_deg", "axial_force_N"});
  CHECK(w.interpolation(0) == kneesim::loads::Interpolation::linear);
  CHECK(w.value(0, 15.0) == doctest::Approx(5.0));
  CHECK(w.value(1, 40.0) == doctest::Approx(250.0));
  CHECK(w.derivative(1, 40.0) == doctest::Approx(-2.5));
  // from 60 % (30) round to 110 % (0): slope -30/50 per %
  CHECK(w.value(0, 85.0) == doctest::Approx(15.0));
  CHECK(w.value(0, 5.0) == doctest::Approx(3.0));
  CHECK(w.value(0, 105.0) == doctest::Approx(3.0));
  CHECK(w.points_pct(0) == std::vector<double>{10, 20, 60});
}

TEST_CASE("key points need not start at 0 or end at 100") {
  Waveform w = Waveform::from_keypoints({{"x_N", {20.0, 70.0}, {1.0, 3.0}}});
  // 70 -> 120 back to 1: midway (95 %) is the average
  CHECK(w.value(0, 95.0) == doctest::Approx(2.0));
  CHECK(w.value(0, 45.0) == doctest::Approx(2.0));
  CHECK(w.value(0, 20.0) == doctest::Approx(1.0));
  CHECK(w.derivative(0, 20.0) == doctest::Approx(0.0));
}

TEST_CASE("conventions flip AP and IE and mirror a left knee") {
  Waveform w = Waveform::from_keypoints({{"flexion_deg", {0, 50}, {0, 10}},
                                         {"ap_force_N", {0, 50}, {1, 2}},
                                         {"ie_torque_Nm", {0, 50}, {3, 4}},
                                         {"ml_mm", {0, 50}, {5, 6}},
                                         {"vv_deg", {0, 50}, {7, 8}}});
  kneesim::loads::WaveformConventions conv;
  conv.ap_sign = -1.0;
  Waveform a = apply_conventions(w, conv);
  CHECK(a.value(1, 0.0) == -1.0);
  CHECK(a.value(2, 0.0) == 3.0);
  CHECK(a.value(0, 50.0) == 10.0);
  conv = {};
  conv.left_knee = true;
  conv.ie_sign = -1.0;
  Waveform b = apply_conventions(w, conv);
  CHECK(b.value(0, 50.0) == 10.0);  // flexion unchanged by the mirror
  CHECK(b.value(1, 0.0) == 1.0);    // AP unchanged
  CHECK(b.value(2, 0.0) == 3.0);    // IE flipped twice: mirror, then ie_sign
  CHECK(b.value(3, 0.0) == -5.0);   // ML mirrored
  CHECK(b.value(4, 0.0) == -7.0);   // VV mirrored
}

TEST_CASE("every load error names the file and the place") {
  TempDir dir;
  const auto missing = dir.path / "nope.csv";
  try {
    load_waveform(missing);
    FAIL("no error for a missing file");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == missing.string() + ": file not found (or not a regular file).");
  }
  CHECK(load_error("gait_pct,a_N\n0,1\n10,x1\n")
            .find(": line 3, column 'a_N': 'x1' is not a "
                  "finite number.") != std::string::npos);
  CHECK(load_error("gait_pct,a_N\n0,1\n10,nan\n").find("'nan' is not a finite number") !=
        std::string::npos);
  CHECK(load_error("gait_pct,a_N,b_N\n0,1,2\n10,1\n")
            .find(": line 3 has 2 cells but the header has 3 columns.") != std::string::npos);
  CHECK(load_error("gait_pct,a_N\n0,1\n10,2\n10,3\n")
            .find(": line 4, column 'gait_pct': 10 does not increase over the previous row's "
                  "value 10 (gait_pct must be strictly increasing).") != std::string::npos);
  CHECK(load_error("gait_pct,a_N\n0,1\n101,2\n")
            .find(": line 3, column 'gait_pct': 101 is outside the allowed range 0..100 %.") !=
        std::string::npos);
  CHECK(load_error("gait_pct,a_N\n-1,1\n10,2\n").find("-1 is outside the allowed range") !=
        std::string::npos);
  CHECK(load_error("gait_pct,a_N\n5,1\n")
            .find("channel 'a_N' has 1 point(s); at least 2 are "
                  "needed.") != std::string::npos);
  CHECK(load_error("time,a_N\n5,1\n").find("the first column must be 'gait_pct', found 'time'") !=
        std::string::npos);
  CHECK(load_error("# only a comment\n").find(": no header line found.") != std::string::npos);
  CHECK(load_error("# form: spline\ngait_pct,a\n0,1\n5,2\n")
            .find("'# form: spline' is not a known form") != std::string::npos);
  // key-point form
  const std::string kp = "# form: keypoints\nchannel,gait_pct,value\n";
  CHECK(load_error(kp + "a_N,0,1\nb_N,0,1\nb_N,5,1\na_N,3,2\na_N,2,3\n")
            .find(": line 7, column 'gait_pct': 2 does not increase over the previous 'a_N' key "
                  "point's value 3") != std::string::npos);
  CHECK(load_error(kp + "a_N,0,1\na_N,x,1\n").find(": line 4, column 'gait_pct': 'x' is not") !=
        std::string::npos);
  CHECK(load_error(kp + "a_N,0,1\na_N,3,1\nb_N,4,1\n")
            .find("channel 'b_N' has 1 point(s); at least 2 are needed.") != std::string::npos);
  CHECK(load_error(kp + "a_N,0,1\na_N,300,1\n").find("300 is outside the allowed range 0..100") !=
        std::string::npos);
  CHECK(load_error("# form: keypoints\ngait_pct,a_N\n0,1\n")
            .find("a keypoints file needs the header 'channel,gait_pct,value'") !=
        std::string::npos);
  // a good file loads without error
  CHECK(load_error(kp + "a_N,0,1\na_N,3,1\n").empty());
}

TEST_CASE("a CSV saved as \"CSV UTF-8\" (byte-order mark) reads like a plain one") {
  // reference: the BOM EF BB BF before the header is an encoding mark, not part of the name
  const std::string body = "gait_pct,a_N\n0,1\n50,3\n";
  CHECK(load_error("\xEF\xBB\xBF" + body).empty());
  TempDir dir;
  const Waveform w = load_waveform(dir.write("bom.csv", "\xEF\xBB\xBF" + body));
  CHECK(w.channel_name(0) == "a_N");
  CHECK(w.value(0, 25.0) == doctest::Approx(2.0));
  // only at the start of the file
  std::string line = "x\xEF\xBB\xBF";
  CHECK_FALSE(kneesim::loads::strip_utf8_bom(line));
}

TEST_CASE("delay_channels: the delayed channel at p is the original at p - d, periodic") {
  // reference: the original waveform evaluated at the shifted time (sampling every 0.1 % with
  // linear interpolation: the error of a half-cosine segment of amplitude A over T % is below
  // A (pi / T)^2 0.1^2 / 8, under 0.01 % of the peak here); zero delays return the waveform
  const Waveform w = Waveform::from_keypoints(
      {{"ap_force_N", {0.0, 8.0, 28.0, 45.0, 60.0}, {0.0, -265.0, -40.0, 110.0, 0.0}},
       {"ie_torque_Nm", {0.0, 5.0, 45.0, 62.0}, {0.0, -1.0, 6.0, 0.0}}});
  const Waveform same = delay_channels(w, {{"ap_force_N", 0.0}});
  CHECK(same.interpolation(0) == w.interpolation(0));
  const Waveform d = delay_channels(w, {{"ap_force_N", 10.0}, {"ie_torque_Nm", -7.5}});
  for (double p : {0.0, 3.3, 18.0, 55.05, 97.2}) {
    CHECK(d.value(d.channel("ap_force_N"), p) ==
          doctest::Approx(w.value(w.channel("ap_force_N"), p - 10.0)).epsilon(1e-4).scale(265.0));
    CHECK(d.value(d.channel("ie_torque_Nm"), p) ==
          doctest::Approx(w.value(w.channel("ie_torque_Nm"), p + 7.5)).epsilon(1e-4).scale(6.0));
  }
  // the peak moves by the delay
  CHECK(d.value(d.channel("ap_force_N"), 18.0) == doctest::Approx(-265.0).epsilon(1e-6));
}

TEST_CASE("a table from a decimal-comma spreadsheet names the separator or the decimal comma") {
  // reference: the text of the files; a decimal comma splits 0,5 into two cells, a ';'- or
  // tab-separated header is one cell, and 0,5 in a tab-separated (.sto-like) cell is no number
  CHECK(load_error("gait_pct,a_N\n0,1\n50,2,5\n")
            .find(": line 3 has 3 cells but the header has 2 columns (likely a decimal comma: 1 "
                  "more comma(s) than the header's; a number written 0,5 is read as two values; "
                  "kneesim reads comma-separated values with a decimal point, e.g. 0.5, not 0,5).") !=
        std::string::npos);
  CHECK(load_error("gait_pct;a_N\n0;1\n50;2,5\n")
            .find(": line 1 (header) 'gait_pct;a_N' is separated by ';', not ','; kneesim reads "
                  "comma-separated values with a decimal point, e.g. 0.5, not 0,5.") !=
        std::string::npos);
  CHECK(load_error("gait_pct\ta_N\n0\t1\n").find("is separated by tabs, not ','") !=
        std::string::npos);
  // fewer cells than the header: no decimal comma to suspect
  CHECK(load_error("gait_pct,a_N,b_N\n0,1,2\n10,1\n")
            .find("the header has 3 columns.") != std::string::npos);
  using kneesim::loads::decimal_comma_hint;
  using kneesim::loads::separator_hint;
  CHECK(decimal_comma_hint("0,5") == " (a decimal comma? write 0.5; kneesim reads numbers with a "
                                     "decimal point)");
  CHECK(decimal_comma_hint("-12,25") .find("write -12.25") != std::string::npos);
  CHECK(decimal_comma_hint("x,5").empty());
  CHECK(decimal_comma_hint("1,2,3").empty());
  CHECK(decimal_comma_hint("0.5").empty());
  CHECK(separator_hint("a;b", "1;2,5", 1, 2).find("separated by ';' with decimal commas ('2,5')") !=
        std::string::npos);
  CHECK(separator_hint("a,b", "1,2", 2, 2).empty());
  CHECK(separator_hint("a,b,c", "1,2", 3, 2).empty());
}
