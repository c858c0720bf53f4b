#include "tools/kneesim/bor_options.h"

#include <algorithm>
#include <cstdlib>

#include "engine/errors.h"

namespace kneesim::cli {

void add_bor_rig_options(CLI::App* cmd, BorRigOptions& o) {
  cmd->add_option("--ring-diameter-mm", o.ring_diameter_mm, "ring diameter [mm]")
      ->capture_default_str()->group("Rig (Hussin 2024 defaults)");
  cmd->add_option("--ring-width-mm", o.ring_width_mm, "ring width = contact length [mm]")
      ->capture_default_str()->group("Rig (Hussin 2024 defaults)");
  cmd->add_option("--block-height-mm", o.block_height_mm, "block height = foundation thickness [mm]")
      ->capture_default_str()->group("Rig (Hussin 2024 defaults)");
  cmd->add_option("--block-width-mm", o.block_width_mm, "block width [mm]")
      ->capture_default_str()->group("Rig (Hussin 2024 defaults)");
  cmd->add_option("--modulus-MPa", o.modulus_MPa, "block Young's modulus [MPa]")
      ->capture_default_str()->group("Rig (Hussin 2024 defaults)");
  cmd->add_option("--poisson", o.poisson, "block Poisson's ratio [-]")
      ->capture_default_str()->group("Rig (Hussin 2024 defaults)");
  cmd->add_option("--friction", o.friction, "ring-block friction coefficient [-]")
      ->capture_default_str()->group("Rig (Hussin 2024 defaults)");
  cmd->add_option("--speed-rpm", o.speed_rpm, "ring speed [rev/min]")
      ->capture_default_str()->group("Rig (Hussin 2024 defaults)");
}

bor::BorRig make_bor_rig(const BorRigOptions& o) {
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
