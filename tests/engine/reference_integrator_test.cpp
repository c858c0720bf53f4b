// SUNDIALS CVODE reference integrator (engine/reference_integrator.h) against the explicit
// central-difference integrator on the same coarse default model (3 mm insert edges), AP and
// IE traces over the last of two cycles. Reference: both solve m qdd = Q(q, qd, t) - c qd
// for the free and force-driven DOFs; CVODE (BDF, rtol 1e-7) is the accurate solution and the
// explicit scheme must agree within the issue-2 bound, 0.2 mm and 0.2 deg RMS, at the step
// the model chose. The explicit run's frames are the steps nearest each 1 % of the cycle
// (within dt/2), CVODE's are exact; that offset is part of the measured difference.
//
// Measured (this file's MESSAGE, 3 mm edges): AP 0.10 mm and IE 0.14 deg RMS at the default
// friction regularization eps = 5 mm/s. The remaining difference is the regularized Coulomb
// friction: its slope mu N / eps (36 400 N s/m at 2600 N) is a damper that the explicit
// velocity update integrates stably only for dt < 2 m / (mu N / eps) ~ 1e-4 s, below the step
// chosen from the contact stiffness (4.4e-4 s), so the carriages chatter slightly while the
// joint sticks. With eps = 1 mm/s (the earlier default) the IE bound was missed (0.17 mm,
// 0.28 deg); with friction off, or eps = 20 mm/s, the integrators agree to 0.01 mm and
// 0.01 deg (reference_long.cpp), which pins the cause.
#include "integrator_agreement.h"

using namespace kneesim;

TEST_CASE("CVODE and central difference agree on AP and IE at the default settings") {
  const test::Agreement a = test::compare_integrators({"implant.edge_length_mm=3"}, 2);
  CHECK(a.ap_rms_mm < 0.2);
  CHECK(a.ie_rms_deg < 0.2);
}
