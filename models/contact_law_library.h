// Where a config's rigid contact law comes from (issue: calibrated contact by default).
//
// The rigid insert's elastic foundation with the material's confined modulus
// K = (1-nu)E/((1+nu)(1-2nu)) over-predicts pressure about twice for UHMWPE against the
// deformable insert (docs/deformable.md); the law calibrated against the deformable insert of
// the same implant and material (kneesim calibrate-contact) is the default. resolve_contact_law
// decides, in this order:
//   1. a deformable insert: no rigid law is used ("unused");
//   2. contact.law_file: that file, checked against the config's implant and material
//      (another material or implant, or meshes changed since: InputError);
//   3. contact.foundation_modulus_MPa > 0: the user's modulus ("modulus");
//   4. contact.calibration = "off": the law as specified, with a one-line warning saying how
//      far such pressures run from the deformable insert on the shipped implants ("specified");
//   5. the law of the config's key (models/contact_law_key.h): found in this process's
//      registry ("calibrated"), in the shipped library models/contact_laws/ ("library"), or in
//      the cache folder ("cache": <cache>/contact_laws/<key>.toml, the distance field's cache
//      folder, models/distance_field_disk.h); none: needs_calibration, and
//      run::ensure_contact_law calibrates it on first use. build_model refuses a rigid Model
//      whose law still needs calibrating, so no path runs the inflated law silently.
// A cache file is used only when its own key equals its name; a cache or library law of the
// same implant path with other mesh content is reported as stale (note) and not used.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "models/config.h"
#include "models/contact_law_file.h"

namespace kneesim::models {

// the shipped laws' folder (source tree) and the cache's (empty when the cache is off)
std::filesystem::path shipped_contact_law_dir();
std::filesystem::path contact_law_cache_dir();

// every shipped law, read once per process (a malformed shipped file throws InputError)
const std::vector<std::pair<std::filesystem::path, CalibratedContactLaw>>& shipped_contact_laws();

// a law calibrated by this process, found by its key from now on
void remember_contact_law(const CalibratedContactLaw& law, const std::filesystem::path& file);

// fills config.contact_law_resolution and, when a law is found, contact.law and the modulus
void resolve_contact_law(Config& config);

// a config without a law of its own (a study trial that varies the material or the implant)
// takes the law of `nominal` scaled by the trials' specified moduli: K_eff(trial) =
// K_eff(nominal) K(trial) / K(nominal), the calibrated ratio K_eff / K carried over (source
// "nominal_ratio", with a note saying so)
void transfer_contact_law(const Config& nominal, Config& trial);

// the one-line warning of the law as specified for a material: how far its stance peak and
// mean pressure ran from the deformable insert on the shipped implants
std::string specified_law_warning(const Config& config);

}  // namespace kneesim::models
