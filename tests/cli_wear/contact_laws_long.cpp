// The shipped calibrated contact laws (models/contact_laws/, made by
// tools/scripts/calibrate_contact_laws.sh) recalibrated from scratch (test_cli_wear_long, label
// "long"; one deformable cycle on the reference mesh, about 48 000 elements, and about 200 short
// rigid runs per material, 3-6 minutes each on the shared 2-core machine):
// `kneesim calibrate-contact --material M` gives the same key and the shipped law: the exponent
// within 0.03 (the outer golden section stops at a 2 % bracket) and the law's pressure at the
// strain g = 0.01 (the stance strains are 0.005-0.02) within 3 % (K_eff alone moves with n:
// 0.01^0.02 = 0.91 for a 0.02 change of n, so K is compared through the pressure it gives), and
// the calibrated law's stance (0-60 %) peak and mean pressure lie within 15 % of the deformable
// insert's (issue 24's acceptance) with the fit not at a search bound. CFR-PEEK's reference lies
// on finer surfaces (its provenance's reference_edge_length_mm and reference_sdf_spacing_mm).
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "models/contact_law_file.h"
#include "models/contact_law_library.h"
#include "tests/cli_wear/cli_helpers.h"

using namespace kneesim;
using namespace kneesim::test;

TEST_CASE("shipped contact laws: recalibrated, the same law, within 15 % of the deformable insert") {
  REQUIRE(!find_kneesim().empty());
  int checked = 0;
  for (const auto& [file, law] : models::shipped_contact_laws()) {
    if (law.implant != "generic") continue;  // the example implants need KNEESIM_DATA's meshes
    CAPTURE(file);
    TempDir tmp;
    const fs::path out = tmp.path / "cal";
    std::vector<std::string> args = {"calibrate-contact", "--material", law.material, "--out",
                                      out.string(), "--no-plots", "--quiet"};
    // the deformable reference's surfaces as the shipped law recorded them (CFR-PEEK's are finer
    // than the rigid runs')
    for (const auto& [key, flag] : {std::pair<std::string, std::string>{"reference_edge_length_mm",
                                                                          "--reference-edge-mm"},
                                    {"reference_sdf_spacing_mm", "--reference-sdf-mm"}}) {
      for (const auto& [k, value] : law.provenance) {
        if (k == key) args.insert(args.end(), {flag, value});
      }
    }
    const Result r = run_kneesim(args, tmp.path);
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    const models::CalibratedContactLaw again = models::read_contact_law_file(out / "contact_law.toml");
    CHECK(again.key.key == law.key.key);
    CHECK(again.exponent == doctest::Approx(law.exponent).epsilon(0.03));
    auto pressure = [](const models::CalibratedContactLaw& l) {
      return l.foundation_modulus_MPa * std::pow(0.01, l.exponent);
    };
    CHECK(pressure(again) == doctest::Approx(pressure(law)).epsilon(0.03));
    const auto s = nlohmann::json::parse(slurp(out / "summary.json"));
    CHECK(s["fit_at_search_bound"] == false);
    const auto& f = s["stance_figures"];
    for (const char* q : {"peak_MPa", "mean_MPa", "mean_peak_MPa"}) {
      CAPTURE(q);
      const double d = f["deformable"][q], c = f["rigid_calibrated"][q];
      MESSAGE(law.material << " stance " << q << ": deformable " << d << ", calibrated " << c);
      CHECK(std::abs(c / d - 1.0) < 0.15);
    }
    ++checked;
  }
  CHECK(checked == 3);
}
