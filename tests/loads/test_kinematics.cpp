// Measured-kinematics reader. References: the data README's key values for the DM subject
// (flexion 5.4 deg at 0 %, 12.3 deg at 15 %, 53.2 deg at 82 %, minimum 7.3 deg near 47 %, AP
// -8.3 to +1.0 mm), the round trip pose -> channels -> pose, and the CSV error messages.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>

#include "engine/errors.h"
#include "loads/iso14243/kinematics.h"
#include "temp_dir.h"

using kneesim::InputError;
using kneesim::loads::read_kinematics;
using kneesim::test::TempDir;

namespace {

std::filesystem::path data_dir() {
  const char* s = std::getenv("KNEESIM_DATA");
  return s ? std::filesystem::path(s) : std::filesystem::path();
}

std::string read_error(const std::filesystem::path& file) {
  try {
    read_kinematics(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("DM fluoroscopic gait matches the README's key values") {
  const auto file = data_dir() / "gc6_dm/fluoroscopic_gait.sto";
  if (!std::filesystem::exists(file)) {
    MESSAGE("skipped: " << file << " absent (set KNEESIM_DATA to the shared data folder)");
    return;
  }
  auto k = read_kinematics(file);
  REQUIRE(k.size() == 101);
  CHECK(k.gait_pct.front() == 0.0);
  CHECK(k.gait_pct.back() == 100.0);
  CHECK(k.flexion_deg[0] == doctest::Approx(5.4).epsilon(0.01));
  CHECK(k.flexion_deg[15] == doctest::Approx(12.3).epsilon(0.01));
  CHECK(k.flexion_deg[82] == doctest::Approx(53.2).epsilon(0.002));
  // stance minimum near 47 %
  int imin = 20;
  for (int i = 20; i < 70; ++i) {
    if (k.flexion_deg[i] < k.flexion_deg[imin]) imin = i;
  }
  CHECK(k.flexion_deg[imin] == doctest::Approx(7.3).epsilon(0.01));
  CHECK(std::abs(imin - 47) <= 3);
  // AP of the insert relative to the femur is the .sto's X translation (X posterior of the
  // femur in the insert frame = anterior of the insert relative to the femur)
  auto [ap_min, ap_max] = std::minmax_element(k.ap_mm.begin(), k.ap_mm.end());
  CHECK(*ap_min == doctest::Approx(-8.3).epsilon(0.01));
  CHECK(*ap_max == doctest::Approx(1.0).epsilon(0.06).scale(0));
  // the README's IE range (-9.7 to +7.4 deg) is the .sto's rotation of the femur about y; the
  // tibia relative to the femur turns the other way: -7.4 to +9.7 deg
  auto [ie_min, ie_max] = std::minmax_element(k.ie_deg.begin(), k.ie_deg.end());
  CHECK(*ie_min == doctest::Approx(-7.4).epsilon(0.01));
  CHECK(*ie_max == doctest::Approx(9.7).epsilon(0.01));
  // the femur sits about 42 mm above the insert base: the insert is inferior
  CHECK(k.is_mm[0] == doctest::Approx(-41.7).epsilon(0.001));
  // the channels describe the same pose as the file (round trip, 1e-12)
  for (std::size_t i = 0; i < k.size(); ++i) {
    auto X = kneesim::loads::pose_from_channels(k.flexion_deg[i], k.ap_mm[i], k.ie_deg[i],
                                                k.ml_mm[i], k.vv_deg[i], k.is_mm[i]);
    CHECK((X.matrix() - k.X_TF[i].matrix()).norm() < 1e-12);
  }
  // the waveform reproduces the samples and is periodic
  auto w = kneesim::loads::to_waveform(k);
  CHECK(w.channel_count() == 6);
  CHECK(w.value(w.channel("flexion_deg"), 82.0) == doctest::Approx(k.flexion_deg[82]));
  CHECK(w.value(w.channel("ie_deg"), 40.5) == doctest::Approx(0.5 * (k.ie_deg[40] + k.ie_deg[41])));
}

TEST_CASE("a femoral reference point moves the reported translation") {
  const auto file = data_dir() / "gc6_dm/fluoroscopic_gait.sto";
  if (!std::filesystem::exists(file)) {
    MESSAGE("skipped: " << file << " absent");
    return;
  }
  // the DM distal arc centre: X 5.5 mm posterior, Y 0.6 mm in the DM femoral frame
  const Eigen::Vector3d p_FC_F(-5.5e-3, 0.6e-3, 0.0);
  auto k0 = read_kinematics(file);
  auto k1 = read_kinematics(file, p_FC_F);
  for (std::size_t i = 0; i < k0.size(); i += 10) {
    const Eigen::Vector3d d = k0.X_TF[i].linear() * p_FC_F * 1000.0;
    CHECK(k1.ap_mm[i] == doctest::Approx(k0.ap_mm[i] - d.x()));
    CHECK(k1.is_mm[i] == doctest::Approx(k0.is_mm[i] - d.y()));
    CHECK(k1.flexion_deg[i] == k0.flexion_deg[i]);
  }
}

TEST_CASE("CSV kinematics: required and optional columns, pose convention") {
  TempDir dir;
  auto file = dir.write("k.csv",
                        "# measured\n"
                        "gait_pct,ie_deg,flexion_deg,ap_mm,vv_deg\n"
                        "0,1,10,-2,0.5\n"
                        "50,2,20,-3,0.5\n");
  auto k = read_kinematics(file);
  CHECK(k.size() == 2);
  CHECK(k.ml_mm.empty());
  CHECK(k.is_mm.empty());
  CHECK(k.vv_deg == std::vector<double>{0.5, 0.5});
  CHECK(k.flexion_deg[1] == 20.0);
  // pure flexion rotates the femur about +z; AP -2 mm puts the femoral origin 2 mm anterior
  auto X = kneesim::loads::pose_from_channels(90.0, -2.0, 0.0, 0.0, 0.0, 0.0);
  CHECK((X.linear() * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm() < 1e-12);
  CHECK(X.translation().x() == doctest::Approx(0.002).scale(0));
  // IE > 0 turns the tibia's anterior toward medial (-z) relative to the femur
  auto Y = kneesim::loads::pose_from_channels(0.0, 0.0, 10.0, 0.0, 0.0, 0.0);
  const Eigen::Vector3d tibia_anterior_in_F = Y.linear().transpose() * Eigen::Vector3d::UnitX();
  CHECK(tibia_anterior_in_F.z() < -0.17);
  auto w = kneesim::loads::to_waveform(k);
  CHECK(w.channel_names() == std::vector<std::string>{"flexion_deg", "ap_mm", "ie_deg", "vv_deg"});
  CHECK(w.value(1, 75.0) == doctest::Approx(-2.5));  // wraps from 50 % (-3) to 100 % (-2)
}

TEST_CASE("the documented 3-column CSV (gait_pct, ap_mm, ie_deg) reads for a comparison") {
  // reference: README and `kneesim run --help` document this form for --measured
  TempDir dir;
  const auto k = read_kinematics(dir.write("m.csv", "gait_pct,ap_mm,ie_deg\n0,1,2\n50,-1,4\n"));
  CHECK(k.size() == 2);
  CHECK(k.flexion_deg.empty());
  CHECK(k.X_TF.empty());  // no pose without flexion
  CHECK(k.ie_deg[1] == 4.0);
  const auto w = kneesim::loads::to_waveform(k);
  CHECK(w.channel_names() == std::vector<std::string>{"ap_mm", "ie_deg"});
}

TEST_CASE("kinematics error messages") {
  TempDir dir;
  CHECK(read_error(dir.write("a.csv", "gait_pct,flexion_deg,ie_deg\n0,1,2\n5,1,2\n"))
            .find(": column 'ap_mm' is missing; required columns are gait_pct, ap_mm, ie_deg "
                  "(optional flexion_deg, ml_mm, vv_deg, is_mm).") != std::string::npos);
  CHECK(read_error(dir.write("b.csv", "gait_pct,flexion_deg,ap_mm,ie_deg\n0,1,2,3\n"))
            .find(": 1 data row(s); at least 2 are needed.") != std::string::npos);
  CHECK(read_error(dir.write("c.csv", "gait_pct,flexion_deg,ap_mm,ie_deg\n0,1,2,3\n5,1,two,3\n"))
            .find(": line 3, column 'ap_mm': 'two' is not a finite number.") != std::string::npos);
  CHECK(read_error(dir.write("d.csv", "gait_pct,flexion_deg,ap_mm,ie_deg\n5,1,2,3\n4,1,2,3\n"))
            .find(": line 3, column 'gait_pct': 4 does not increase over the previous row (5).") !=
        std::string::npos);
  CHECK(read_error(dir.write("e.csv", "gait_pct,flexion_deg,ap_mm,ie_deg\n0,1,2,3\n150,1,2,3\n"))
            .find(": line 3, column 'gait_pct': 150 is outside the allowed range 0..100 %.") !=
        std::string::npos);
  CHECK(read_error(dir.write("f.sto", "version=1\ntime\tknee_ant_r\n0\t1\n"))
            .find("no 'endheader' line found") != std::string::npos);
  CHECK(read_error(dir.write("g.sto", "endheader\ntime\tknee_ant_r\n0\t1\n"))
            .find(": column 'knee_sup_r' is missing") != std::string::npos);
  CHECK(read_error(dir.path / "missing.sto").find("file not found") != std::string::npos);
}
