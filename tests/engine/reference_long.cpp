// CVODE vs central difference with the friction regularization inside the explicit step's
// stability (long suite: two CVODE runs of ~1e5 internal steps each). Reference: the
// integrators solve the same equations, so once the explicit scheme is stable for every force
// (here eps = 20 mm/s: mu N dt / (m eps) = 0.07 * 2600 * 4.4e-4 / (2 * 0.02) = 2.0 at peak
// load, at the edge of the explicit damper limit 2) the traces agree 4x inside the issue-2
// bound of 0.2 mm and 0.2 deg RMS. Since the step integrates the friction's viscous slope
// implicitly (engine/step.cpp; stable for any eps), that term is first order in dt: measured
// 0.033 mm / 0.026 deg here (0.0098 / 0.0085 with the earlier explicit friction), hence
// 0.05 mm / 0.05 deg. The friction-free case below still pins the rest to 0.02. Together with reference_integrator_test.cpp this pins the
// default-settings difference on the regularized friction (see that file's header). The
// default settings at the default 1 mm resolution are checked here too (a CVODE run of
// ~10 s).
#include "integrator_agreement.h"

using namespace kneesim;

TEST_CASE("CVODE and central difference agree closely when friction is inside the stable step") {
  const test::Agreement a = test::compare_integrators(
      {"implant.edge_length_mm=3", "contact.friction_regularization_mm_per_s=20"}, 2);
  CHECK(a.ap_rms_mm < 0.05);
  CHECK(a.ie_rms_deg < 0.05);
}

TEST_CASE("CVODE and central difference agree without friction") {
  const test::Agreement a =
      test::compare_integrators({"implant.edge_length_mm=3", "contact.friction=0"}, 2);
  CHECK(a.ap_rms_mm < 0.02);
  CHECK(a.ie_rms_deg < 0.02);
}

TEST_CASE("CVODE and central difference at the default resolution (1 mm edges)") {
  // the default settings at the default insert resolution: the same acceptance bound
  const test::Agreement a = test::compare_integrators({"implant.edge_length_mm=1"}, 2);
  CHECK(a.ap_rms_mm < 0.2);
  CHECK(a.ie_rms_deg < 0.2);
}
