// A contact-law calibration whose fit ends at a bound of its search (0.01 to 10 K) is refused
// (analysis/run/calibrate_contact_law.h): one sentence naming the material, the implant, the
// value and the range, so no law at a bound is ever written or used. Inside: accepted.
#include <doctest/doctest.h>

#include "analysis/run/calibrate_contact_law.h"
#include "engine/errors.h"

using namespace kneesim;

TEST_CASE("contact-law calibration: a fit at a search bound is refused, one inside accepted") {
  const double k = 4116.0;
  CHECK_NOTHROW(run::check_fit_inside_search(0.348 * k, k, "uhmwpe", "generic", "/tmp/x"));
  CHECK_NOTHROW(run::check_fit_inside_search(1.36 * k, k, "peek", "generic", "/tmp/x"));
  CHECK_THROWS_WITH_AS(run::check_fit_inside_search(0.0101 * k, k, "uhmwpe", "generic", "/tmp/x"),
                       doctest::Contains("material \"uhmwpe\" on implant \"generic\" ended at the "
                                         "search bound K_eff = 41.5716 MPa (search 41.16 to 41160 MPa"),
                       InputError);
  CHECK_THROWS_AS(run::check_fit_inside_search(9.9 * k, k, "cfr-peek", "/x/insert.stl", "/tmp/x"),
                  InputError);
}
