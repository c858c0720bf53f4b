// The contact footprint of a rigid cycle (models/contact_footprint.h), its pure parts against
// closed forms: merged intervals, the second-moment width of a Hertz patch (2 a for
// p = p0 sqrt(1 - r^2/a^2), exactly in the continuum, within the sampling error on a grid),
// percentiles; and on the built-in implant: the loaded contact lies on both condyles, inside
// the insert, and a stiffer insert's patches are narrower.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/contact_law.h"
#include "models/build_model.h"
#include "models/config.h"
#include "models/contact_footprint.h"

using namespace kneesim;
using namespace kneesim::models;

TEST_CASE("footprint: merged intervals, Hertz patch width, percentiles") {
  // gaps of 0.5 (closed by the margins 2 x 0.3), 1.0 and 6.0 (kept open)
  const auto m = merge_intervals({{3, 4}, {0, 1}, {1.5, 2}, {10, 11}}, 0.3);
  REQUIRE(m.size() == 3u);
  CHECK(m[0].lo == doctest::Approx(-0.3));
  CHECK(m[0].hi == doctest::Approx(2.3));
  CHECK(m[1].lo == doctest::Approx(2.7));
  CHECK(m[1].hi == doctest::Approx(4.3));
  CHECK(m[2].lo == doctest::Approx(9.7));

  // a circular Hertz patch of radius a = 2 mm, and one stretched to 5 mm along z, sampled on a
  // 0.02 mm grid: widths 2 a
  for (const double az : {2e-3, 5e-3}) {
    const double ax = 2e-3;
    std::vector<double> x, z, p;
    for (double u = -ax; u <= ax; u += 2e-5)
      for (double w = -az; w <= az; w += 2e-5) {
        const double s = 1.0 - u * u / (ax * ax) - w * w / (az * az);
        if (s <= 0.0) continue;
        x.push_back(u + 1e-3);  // off the origin: the mean is removed
        z.push_back(w);
        p.push_back(std::sqrt(s));
      }
    const auto [wx, wz] = calc_patch_widths(x, z, p);
    CHECK(wx == doctest::Approx(2 * ax).epsilon(0.01));
    CHECK(wz == doctest::Approx(2 * az).epsilon(0.01));
  }
  CHECK(calc_patch_widths({}, {}, {}) == std::pair<double, double>{0.0, 0.0});
  CHECK(find_percentile({5, 1, 4, 2, 3, 6, 7, 8, 9, 10}, 0.1) == 2);
  CHECK(find_percentile({}, 0.1) == 0);
}

TEST_CASE("footprint of the built-in implant: both condyles, and a stiffer insert's narrower patches") {
  auto footprint = [](const char* material) {
    const Config c = load_config({}, {{"material.name", std::string("\"") + material + "\""},
                                      {"implant.edge_length_mm", "2"},
                                      {"gait.period_s", "0.2"}});
    const BuiltModel b = build_model(c);
    const double k = engine::foundation_modulus(c.material.elastic_modulus_MPa * 1e6, c.material.poisson);
    return find_contact_footprint(b.model, k, c.dt_safety, 2e-3);
  };
  const ContactFootprint soft = footprint("uhmwpe");
  REQUIRE(soft.z.size() == 2u);  // medial and lateral
  CHECK(soft.z[0].hi < 0.0);
  CHECK(soft.z[1].lo > 0.0);
  REQUIRE(soft.x.size() == 1u);
  CHECK(soft.x[0].lo > -0.023 - 2e-3);  // within the 46 mm deep insert and the 2 mm margin
  CHECK(soft.x[0].hi < 0.023 + 2e-3);
  CHECK(soft.layer_thickness > 0.006);
  const ContactFootprint stiff = footprint("cfr-peek");
  const double soft_w = find_percentile(soft.width_x, 0.1), stiff_w = find_percentile(stiff.width_x, 0.1);
  MESSAGE("10th-percentile AP patch width: uhmwpe " << soft_w * 1e3 << " mm, cfr-peek " << stiff_w * 1e3 << " mm");
  CHECK(stiff_w < soft_w);
}
