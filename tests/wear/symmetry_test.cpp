// Symmetric loading of a symmetric implant gives symmetric wear (issue 3 acceptance).
//
// The generic implant's vertices are mirror-symmetric about the sagittal plane z = 0 (checked
// first, to rounding), but its triangulation is not: every quad of the insert grid is split
// along the same diagonal, so a dish is not the mirror image of itself, while the lateral dish
// is an exact translate (by the condyle spacing) of the medial one, as are the condyles.
// With the load line and the tibial pivot on the midline and no IE torque:
//  - all tibial rotations and ML locked: both condyles see translated copies of the same
//    contact, so medial and lateral volumes agree to rounding (1e-9 relative);
//  - the stanmore rig's free ML, VV and IE: the diagonal asymmetry gives both condyles the
//    same small ML friction/contact force, the tibia drifts ~0.06 mm in ML and, its light IE
//    (3e-5 kg m^2) following the asymmetry's small friction moment, +-0.025 deg in IE; the
//    volumes differ by 3.0e-3 (measured with the calibrated law p = K_eff g^0.63, whose flatter
//    pressure weights the patch border, where the diagonals differ, more than the n = 1 law's
//    1.04e-3). The tolerance is 6e-3, 2x that, while a 1 mm medial offset of the tibial VV pivot
//    (the control run below, printed: 8.8e-2) exceeds it 15 times, so the test can fail.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "models/build_model.h"
#include "tests/wear/wear_fixtures.h"
#include "wear/archard.h"
#include "wear/wear_loop.h"

using namespace kneesim;

namespace {

// index of the mirror image (z -> -z) of every vertex, -1 when there is none within 1e-9 m
std::vector<int> mirror_map(const std::vector<Eigen::Vector3d>& v) {
  auto key = [](const Eigen::Vector3d& p) {
    return std::array<long long, 3>{std::llround(p.x() * 1e9), std::llround(p.y() * 1e9),
                                    std::llround(p.z() * 1e9)};
  };
  std::map<std::array<long long, 3>, int> index;
  for (size_t i = 0; i < v.size(); ++i) index[key(v[i])] = static_cast<int>(i);
  std::vector<int> mirror(v.size(), -1);
  for (size_t i = 0; i < v.size(); ++i) {
    const auto it = index.find(key(Eigen::Vector3d(v[i].x(), v[i].y(), -v[i].z())));
    if (it != index.end()) mirror[i] = it->second;
  }
  return mirror;
}

double mirror_error(const std::vector<Eigen::Vector3d>& v, const std::vector<int>& mirror) {
  double worst = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    if (mirror[i] < 0) return 1.0;
    worst = std::max(worst,
                     (v[mirror[i]] - Eigen::Vector3d(v[i].x(), v[i].y(), -v[i].z())).norm());
  }
  return worst;
}

const std::vector<models::Override> kSymmetric = {{"rig.axial_offset_mm", "0"},
                                                  {"rig.tibia_pivot_medial_mm", "0"},
                                                  {"gait.ie_torque_scale", "0"}};

struct SideVolumes {
  double medial = 0.0, lateral = 0.0;  // [m^3]
  double max_ml = 0.0, max_vv = 0.0;   // largest |tibial ML| [m] and |VV| [rad] of the last cycle
  double rel() const { return std::abs(medial - lateral) / (0.5 * (medial + lateral)); }
};

SideVolumes run(std::vector<models::Override> overrides, long cycles, long every) {
  const auto t0 = std::chrono::steady_clock::now();
  const models::BuiltModel built = models::build_model(test::coarse_config(overrides));
  wear::WearOptions o;
  o.total_cycles = cycles;
  o.update_every = every;
  o.law.wear_factor = built.material.wear_factor_mm3_per_Nmm * wear::kWearFactorSI;
  o.law.friction = built.model.contact.friction;
  const wear::WearResult r = wear::run_wear(built, o);
  REQUIRE(r.status == engine::StepStatus::kOk);
  SideVolumes s;
  s.medial = r.records.back().medial_volume;
  s.lateral = r.records.back().lateral_volume;
  for (const auto& f : r.frames) {
    s.max_ml = std::max(s.max_ml, std::abs(f.joint.ml));
    s.max_vv = std::max(s.max_vv, std::abs(f.joint.vv));
  }
  std::printf("[wear] symmetry run: medial %.5f mm^3, lateral %.5f mm^3, relative difference "
              "%.3e, max |ML| %.4f mm, max |VV| %.4f deg, %.2f s\n",
              s.medial * 1e9, s.lateral * 1e9, s.rel(), s.max_ml * 1e3, s.max_vv * 57.29578,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return s;
}

}  // namespace

TEST_CASE("the generic implant is mirror-symmetric about the sagittal plane (vertices)") {
  // reference: the generic TKR is defined symmetric (condyles and dishes at z = -+s/2);
  // tolerance 1e-15 m, rounding of millimetre-scale coordinates
  const models::BuiltModel built = models::build_model(test::coarse_config());
  const auto& s = built.model.insert;
  CHECK(mirror_error(s.vertices_T, mirror_map(s.vertices_T)) < 1e-15);
  CHECK(mirror_error(built.implant.femur.vertices, mirror_map(built.implant.femur.vertices)) <
        1e-15);
  // the triangulation is not (documented above): count the articular triangles whose mirror
  // image is a triangle too, for the record
  const std::vector<int> mirror = mirror_map(s.vertices_T);
  std::set<std::array<int, 3>> tris;
  for (const auto& t : s.triangles) {
    std::array<int, 3> a{t[0], t[1], t[2]};
    std::sort(a.begin(), a.end());
    tris.insert(a);
  }
  int matched = 0;
  for (const auto& t : s.triangles) {
    std::array<int, 3> a{mirror[t[0]], mirror[t[1]], mirror[t[2]]};
    std::sort(a.begin(), a.end());
    matched += static_cast<int>(tris.count(a));
  }
  std::printf("[wear] articular triangles %d, with a mirror-image triangle %d\n", s.size(),
              matched);
}

TEST_CASE("symmetric loading of the symmetric implant: medial = lateral wear") {
  SUBCASE("stanmore rig, ML, VV and IE free: within 6e-3") {
    const SideVolumes s = run(kSymmetric, 1'000'000, 500'000);
    MESSAGE("symmetric, free: medial/lateral volumes differ by " << s.rel());
    CHECK(s.medial > 0.0);
    CHECK(s.rel() < 6e-3);
    CHECK(s.max_ml < 1e-4);  // the midline loading keeps the tibia centred (0.1 mm)
  }
  SUBCASE("tibial ML, VV and IE locked: equal to rounding (translated condyles)") {
    std::vector<models::Override> o = kSymmetric;
    o.push_back({"rig.tibia.ml", "locked"});
    o.push_back({"rig.tibia.vv", "locked"});
    o.push_back({"rig.tibia.ie", "locked"});
    const SideVolumes s = run(o, 500'000, 500'000);
    CHECK(s.medial > 0.0);
    CHECK(s.rel() < 1e-9);
  }
  SUBCASE("control: a 1 mm medial offset of the tibial VV pivot exceeds the tolerance") {
    // on the stanmore rig the femoral VV is locked, so the medial-lateral load share is set
    // by the tibial VV pivot (rig.axial_offset_mm alone changes nothing there: measured)
    std::vector<models::Override> o = kSymmetric;
    o[1] = {"rig.tibia_pivot_medial_mm", "1"};
    const SideVolumes s = run(o, 500'000, 500'000);
    MESSAGE("control, 1 mm VV pivot offset: medial/lateral volumes differ by " << s.rel());
    CHECK(s.rel() > 1e-2);
    CHECK(s.medial > s.lateral);  // a positive offset is medial (config.h)
  }
}
