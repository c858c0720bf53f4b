// Checking a rigid config's contact law against the deformable insert under the config's own
// load case: `kneesim check-contact` is the shell.
//
// Why: a calibrated law (analysis/run/calibrate_contact_law.h) is fitted on one reference load
// case (the stanmore rig, the shipped gait, 0-30 % of the cycle) and looked up for every load
// case of the same implant, material and surfaces. docs/validation.md shows how far it carries
// to other rig presets and loads; a user whose rig, gait or load differs from those checks it
// on their own: one deformable gait cycle (on the calibration's reference mesh unless the
// config sets [deformable] keys, and on the surfaces the law's provenance names as its
// reference's), the rigid insert with the law every command uses, and the
// rigid insert with the law as specified, compared frame by frame over stance with the
// calibration's error measure (analysis/run/contact_calibration.h). Nothing is fitted.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "models/config.h"

namespace kneesim::run {

struct ContactLawCheckJob {
  // the rigid config as every command loads it: its law (calibrated on first use when the
  // config asks for that) is the one checked
  models::Config config;
  // the same config with its law as specified (contact.calibration = "off", no law file, no
  // modulus), shown beside it; the deformable insert runs on this config's [deformable] keys
  models::Config specified;
  std::filesystem::path out;  // runs and outputs
  bool plots = true;          // out/calibration.png and the runs' plots
  bool quiet = false;         // no progress lines on stderr
};

// runs the check; writes out/comparison.csv (the three traces, as calibrate-contact's),
// out/summary.json (the law, the stance figures of the three runs, the frame errors of both
// laws over 0-30 %, 30-60 % and stance, the law's stance peak, mean and area differences) and
// out/calibration.png; the runs stay in out/deformable, out/rigid (as specified) and
// out/rigid_law. InputError for a deformable config (the check runs both inserts itself) and
// for a specified config that is not the law as specified; a failed run throws as run_gait_job
// does. Returns summary.json
nlohmann::json check_contact_law(const ContactLawCheckJob& job);

}  // namespace kneesim::run
