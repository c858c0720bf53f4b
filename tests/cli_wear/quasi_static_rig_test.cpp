// The rig is quasi-static: halving or doubling each carriage mass, rotary inertia and damper
// moves the AP and IE ranges of motion of `kneesim run` by less than 2 % (issue 24 item 4).
// Reference: a 1 Hz gait on a rig whose inertia and dampers matter neither for the load path
// nor for the motion has ranges of motion independent of them (the quasi-static limit); the
// masses and dampers are this project's assumptions (models/config.h), so the ranges must not
// depend on them. Both force-controlled rig layouts: stanmore (tibia free in AP, IE, ML, VV)
// and materials_study (femur free in AP, ML, VV).
// Not included: rig.is_mass_kg, the femur's axial mass, which sets the time step (its effect
// on the ranges is the step's, docs/validation.md#carriage-masses), and rig.fe_inertia_kgm2
// (FE is prescribed in every preset). The default model (1 mm insert edges, default step): on
// 2 mm edges the IE range's heel-strike transient, itself not step-converged to a few per cent
// (docs/validation.md#carriage-masses, the step's row), moved by 2.2 % when the ML mass was
// halved (default step) or the VV inertia doubled (dt_safety 0.4).
// Measured (this file's MESSAGE): at most about 1.2 %.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "tests/cli_wear/cli_helpers.h"

using namespace kneesim::test;

namespace {

std::pair<double, double> ranges(const std::string& preset, const std::string& set,
                                 const TempDir& tmp, const std::string& name) {
  const fs::path out = tmp.path / name;
  std::vector<std::string> args = {"run", "--quiet", "--no-plots", "--set",
                                   "rig.preset=" + preset, "--out", out.string()};
  if (!set.empty()) args.insert(args.end(), {"--set", set});
  const Result r = run_kneesim(args, tmp.path, name);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  const auto s = nlohmann::json::parse(slurp(out / "summary.json"));
  return {s["ap_rom_mm"].get<double>(), s["ie_rom_deg"].get<double>()};
}

}  // namespace

TEST_CASE("halving or doubling any carriage mass or damper moves AP and IE range by < 2 %") {
  REQUIRE(!find_kneesim().empty());
  // key and its default (models/config.h)
  const std::vector<std::pair<std::string, double>> keys = {
      {"rig.ap_mass_kg", 0.06},           {"rig.ml_mass_kg", 0.25},
      {"rig.vv_inertia_kgm2", 0.01},      {"rig.ie_inertia_kgm2", 3e-5},
      {"rig.ap_damping_Ns_per_m", 1.0},   {"rig.ml_damping_Ns_per_m", 5.0},
      {"rig.ie_damping_Nms_per_rad", 0.003}, {"rig.vv_damping_Nms_per_rad", 0.01}};
  for (const std::string preset : {"stanmore", "materials_study"}) {
    CAPTURE(preset);
    TempDir tmp;
    const auto [ap0, ie0] = ranges(preset, "", tmp, "base");
    double worst = 0.0;
    int n = 0;
    for (const auto& [key, value] : keys) {
      for (double f : {0.5, 2.0}) {
        const std::string set = key + "=" + std::to_string(value * f);
        CAPTURE(set);
        const auto [ap, ie] = ranges(preset, set, tmp, "r" + std::to_string(n++));
        const double d_ap = 100.0 * (ap / ap0 - 1.0), d_ie = 100.0 * (ie / ie0 - 1.0);
        CHECK(std::abs(d_ap) < 2.0);
        CHECK(std::abs(d_ie) < 2.0);
        worst = std::max({worst, std::abs(d_ap), std::abs(d_ie)});
      }
    }
    MESSAGE(preset << ": AP " << ap0 << " mm, IE " << ie0 << " deg; largest change "
                   << worst << " %");
  }
}
