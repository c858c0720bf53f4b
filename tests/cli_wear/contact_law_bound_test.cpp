// A contact-law calibration whose fit ends at a bound of its search (the modulus 0.01 to 10 times
// the search's reference, the exponent 0.3 to 1.5) is refused
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
  // the exponent's search, 0.3 to 1.5: within 2 % of a bound refused
  CHECK_NOTHROW(run::check_exponent_inside_search(0.63, "uhmwpe", "generic", "/tmp/x"));
  CHECK_THROWS_WITH_AS(run::check_exponent_inside_search(1.49, "cfr-peek", "generic", "/tmp/x"),
                       doctest::Contains("ended at the search bound of the exponent n = 1.49"),
                       InputError);
  CHECK_THROWS_AS(run::check_exponent_inside_search(0.305, "peek", "generic", "/tmp/x"), InputError);
  // the modulus search follows the exponent: centred on the modulus that gives the law as
  // specified's pressure at g = 0.01 (K for n = 1; 10 K for n = 1.5, 0.1 K for n = 0.5)
  CHECK(run::modulus_search_reference(k, 1.0) == doctest::Approx(k));
  CHECK(run::modulus_search_reference(k, 1.5) == doctest::Approx(10.0 * k));
  CHECK(run::modulus_search_reference(k, 0.5) == doctest::Approx(0.1 * k));
}
