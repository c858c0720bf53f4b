#include "wear/bor/bor_rig.h"

#include <cmath>
#include <cstdio>

#include "engine/errors.h"

namespace kneesim::bor {

double foundation_constant(const BorRig& rig) {
  const double nu = rig.poisson_ratio;
  return (1.0 - nu) * rig.youngs_modulus / ((1.0 + nu) * (1.0 - 2.0 * nu) * rig.block_height);
}

double sliding_distance_per_cycle(const BorRig& rig) { return 2.0 * M_PI * rig.ring_radius; }

double seconds_per_cycle(const BorRig& rig) { return 60.0 / rig.speed_rpm; }

double sarkar_factor(double friction) { return std::sqrt(1.0 + 3.0 * friction * friction); }

namespace {

void check_range(const std::string& source, const char* field, double value, double lo,
                 double hi, double to_io, const char* unit) {
  if (std::isfinite(value) && value > lo && value <= hi) return;
  char buf[320];
  std::snprintf(buf, sizeof buf, "%s: %s = %g %s is outside the allowed range (%g, %g] %s.",
                source.c_str(), field, value * to_io, unit, lo * to_io, hi * to_io, unit);
  throw InputError(buf);
}

}  // namespace

void check_rig(const BorRig& rig, const std::string& source) {
  check_range(source, "ring radius", rig.ring_radius, 0.0, 1.0, 1e3, "mm");
  check_range(source, "ring width", rig.ring_width, 0.0, 1.0, 1e3, "mm");
  check_range(source, "block height", rig.block_height, 0.0, 1.0, 1e3, "mm");
  check_range(source, "block width", rig.block_width, 0.0, 1.0, 1e3, "mm");
  check_range(source, "block length", rig.block_length, 0.0, 1.0, 1e3, "mm");
  check_range(source, "Young's modulus", rig.youngs_modulus, 0.0, 1e12, 1e-6, "MPa");
  check_range(source, "Poisson's ratio", rig.poisson_ratio, -1.0, 0.4999, 1.0, "");
  check_range(source, "friction coefficient", rig.friction, -1e-300, 2.0, 1.0, "");
  check_range(source, "ring speed", rig.speed_rpm, 0.0, 1e5, 1.0, "rpm");
  if (rig.ring_width > rig.block_width) {
    char buf[240];
    std::snprintf(buf, sizeof buf,
                  "%s: ring width %g mm exceeds block width %g mm; the ring must sit on the block.",
                  source.c_str(), rig.ring_width * 1e3, rig.block_width * 1e3);
    throw InputError(buf);
  }
}

}  // namespace kneesim::bor
