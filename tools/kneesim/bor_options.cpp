#include "tools/kneesim/bor_options.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "engine/errors.h"
#include "tools/kneesim/commands.h"

namespace kneesim::cli {
namespace {

// the rig options' allowed ranges as messages name them (those of bor::check_rig, in the
// options' units)
constexpr struct {
  const char* ring_diameter = "(0, 2000] mm";
  const char* ring_width = "(0, 1000] mm, at most --block-width-mm";
  const char* length = "(0, 1000] mm";
  const char* modulus = "(0, 1e6] MPa";
  const char* poisson = "(-1, 0.4999]";
  const char* friction = "[0, 2]";
  const char* speed = "(0, 1e5] rpm";
} kRange;

}  // namespace

void add_bor_rig_options(CLI::App* cmd, BorRigOptions& o) {
  const char* group = "Rig (Hussin 2024 defaults)";
  cmd->add_option("--ring-diameter-mm", o.ring_diameter_mm, "ring diameter [mm]")
      ->capture_default_str()->group(group)->check(finite_number(kRange.ring_diameter));
  cmd->add_option("--ring-width-mm", o.ring_width_mm, "ring width = contact length [mm]")
      ->capture_default_str()->group(group)->check(finite_number(kRange.ring_width));
  cmd->add_option("--block-height-mm", o.block_height_mm, "block height = foundation thickness [mm]")
      ->capture_default_str()->group(group)->check(finite_number(kRange.length));
  cmd->add_option("--block-width-mm", o.block_width_mm, "block width [mm]")
      ->capture_default_str()->group(group)->check(finite_number(kRange.length));
  cmd->add_option("--modulus-MPa", o.modulus_MPa, "block Young's modulus [MPa]")
      ->capture_default_str()->group(group)->check(finite_number(kRange.modulus));
  cmd->add_option("--poisson", o.poisson, "block Poisson's ratio [-]")
      ->capture_default_str()->group(group)->check(finite_number(kRange.poisson));
  cmd->add_option("--friction", o.friction, "ring-block friction coefficient [-]")
      ->capture_default_str()->group(group)->check(finite_number(kRange.friction));
  cmd->add_option("--speed-rpm", o.speed_rpm, "ring speed [rev/min]")
      ->capture_default_str()->group(group)->check(finite_number(kRange.speed));
}

bor::BorRig make_bor_rig(const BorRigOptions& o) {
  // each option by its own name and in its own unit (bor::check_rig below names the rig's
  // quantities in SI terms, e.g. the ring radius, for rigs that come from elsewhere)
  auto in = [](const char* flag, double v, double lo, bool lo_open, double hi, const char* range) {
    if (!(std::isfinite(v) && (lo_open ? v > lo : v >= lo) && v <= hi)) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "command line: %s = %g is outside the allowed range %s.", flag,
                    v, range);
      throw InputError(buf);
    }
  };
  in("--ring-diameter-mm", o.ring_diameter_mm, 0.0, true, 2000.0, kRange.ring_diameter);
  in("--ring-width-mm", o.ring_width_mm, 0.0, true, 1000.0, kRange.ring_width);
  in("--block-height-mm", o.block_height_mm, 0.0, true, 1000.0, kRange.length);
  in("--block-width-mm", o.block_width_mm, 0.0, true, 1000.0, kRange.length);
  in("--modulus-MPa", o.modulus_MPa, 0.0, true, 1e6, kRange.modulus);
  in("--poisson", o.poisson, -1.0, true, 0.4999, kRange.poisson);
  in("--friction", o.friction, 0.0, false, 2.0, kRange.friction);
  in("--speed-rpm", o.speed_rpm, 0.0, true, 1e5, kRange.speed);
  if (o.ring_width_mm > o.block_width_mm) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "command line: --ring-width-mm = %g exceeds --block-width-mm = "
                  "%g; the ring must sit on the block (ring width <= block width).",
                  o.ring_width_mm, o.block_width_mm);
    throw InputError(buf);
  }
  bor::BorRig rig;
  rig.ring_radius = 0.5e-3 * o.ring_diameter_mm;
  rig.ring_width = 1e-3 * o.ring_width_mm;
  rig.block_height = 1e-3 * o.block_height_mm;
  rig.block_width = 1e-3 * o.block_width_mm;
  rig.youngs_modulus = 1e6 * o.modulus_MPa;
  rig.poisson_ratio = o.poisson;
  rig.friction = o.friction;
  rig.speed_rpm = o.speed_rpm;
  bor::check_rig(rig, "command line");
  return rig;
}

void apply_effect_params(bor::BorWearLaw law, const std::vector<std::string>& assignments,
                         bor::BorWearParams& params) {
  const auto allowed = bor::wear_law_param_names(law);
  std::string allowed_text;
  for (const auto& a : allowed) allowed_text += (allowed_text.empty() ? "" : ", ") + a;
  if (allowed_text.empty()) allowed_text = "none";
  for (const auto& text : assignments) {
    const auto eq = text.find('=');
    const std::string name = text.substr(0, eq);
    char* end = nullptr;
    const double value =
        (eq == std::string::npos) ? 0.0 : std::strtod(text.c_str() + eq + 1, &end);
    if (eq == std::string::npos || end == text.c_str() + eq + 1 || *end != '\0') {
      throw InputError("command line: --effect-param '" + text +
                       "' is not of the form name=value (a number).");
    }
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      throw InputError("command line: --effect-param '" + name + "' does not belong to effect " +
                       std::string(bor::wear_law_name(law)) + "; its parameters are: " +
                       allowed_text + ".");
    }
    bor::set_wear_param(params, name, value, "command line --effect-param");
  }
}

}  // namespace kneesim::cli
