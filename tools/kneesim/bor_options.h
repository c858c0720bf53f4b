// Command-line options shared by `kneesim bor` and `kneesim diagnose bor`: the block-on-ring rig
// (defaults: Hussin 2024) in I/O units, and the wear law with its effect parameters.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "wear/bor/bor_rig.h"
#include "wear/bor/bor_wear_law.h"

namespace kneesim::cli {

struct BorRigOptions {
  double ring_diameter_mm = 35.0;   // [mm]
  double ring_width_mm = 10.0;      // [mm]
  double block_height_mm = 12.0;    // [mm]
  double block_width_mm = 12.0;     // [mm]
  double modulus_MPa = 690.0;       // [MPa]
  double poisson = 0.317;           // [-]
  double friction = 0.19;           // [-]
  double speed_rpm = 1000.0;        // [rev/min]
};

void add_bor_rig_options(CLI::App* cmd, BorRigOptions& o);
// SI rig, validated (InputError naming the option)
bor::BorRig make_bor_rig(const BorRigOptions& o);

// parses "--effect-param name=value" strings into `params` for `law`; InputError names the
// option, the text and what is allowed
void apply_effect_params(bor::BorWearLaw law, const std::vector<std::string>& assignments,
                         bor::BorWearParams& params);

}  // namespace kneesim::cli
