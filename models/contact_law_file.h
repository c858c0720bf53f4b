// A calibrated elastic-foundation law for the rigid insert: written by `kneesim calibrate-contact`
// (and by the calibration on first use), shipped for the built-in and example implants in
// models/contact_laws/, cached per key (models/contact_law_library.h), or named by a config as
// contact.law_file. The file holds the law the rigid path uses (the nonlinear or linear
// foundation law of physics.md section 4 raised to an exponent, engine/contact_law.h) with an
// effective foundation modulus and the exponent fitted against
// the deformable insert, what it belongs to (models/contact_law_key.h: the implant, material
// and settings hashes and the key), and how it was made:
//
//   [calibrated_contact]
//   material = "uhmwpe"              # the config's material.name
//   implant = "generic"              # "generic" or the insert mesh path as the config names it
//   key = "..."                      # hex hashes (models/contact_law_key.h)
//   implant_hash = "..."
//   material_hash = "..."
//   settings_hash = "..."
//   law = "nonlinear"                # contact.law
//   foundation_modulus_MPa = 1433.0  # K_eff, replaces K = (1-nu)E/((1+nu)(1-2nu))
//   exponent = 0.7                   # n of p = K_eff g^n (absent: 1)
//   specified_modulus_MPa = 4116.2   # K of the material, for the record
//   fitted_on = "..."                # what it was fitted on, for the record
//   [calibrated_contact.provenance]  # command, deformable mesh, errors, run times (any keys)
//
// Why a fitted modulus and exponent and not a tabulated law: the rigid path's pressure at an
// element is a function of its own penetration only; what the deformable insert adds is load
// spreading (a neighbour's penetration), which no pointwise law can carry. A pointwise law has
// two things to trade: how deep the femur sinks for the load (the modulus: contact area
// against pressure) and the shape of the patch's pressure (the exponent: its peak over its
// mean). docs/validation.md gives the errors it leaves per implant and material.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "models/contact_law_key.h"

namespace kneesim::models {

struct CalibratedContactLaw {
  std::string material;              // material name
  std::string implant;               // "generic" or the insert mesh path
  ContactLawKey key;                 // what the law belongs to
  std::string law = "nonlinear";     // "linear" | "nonlinear"
  double foundation_modulus_MPa = 0.0;   // K_eff [MPa]
  double exponent = 1.0;                 // n of p = K_eff g^n (engine/contact_law.h) [-]
  double specified_modulus_MPa = 0.0;    // K of the material [MPa]
  std::string fitted_on;             // description
  // how it was made: key -> value in TOML syntax (a quoted string or a number), in file order
  std::vector<std::pair<std::string, std::string>> provenance;
};

// a TOML basic string: s in double quotes, its quotes and backslashes escaped (law files and
// their provenance values)
std::string toml_quoted(const std::string& s);

// reads a law file and checks its values; InputError (one sentence naming the file, the key,
// the value and what is allowed) for a missing or malformed file or a value out of range
CalibratedContactLaw read_contact_law_file(const std::filesystem::path& file);

// InputError naming `file` when the law was calibrated for another material (name or
// constants) or another implant (the geometry's hash: another implant, or its meshes changed
// since) than `material` / `key` describe
void check_contact_law_fits(const std::filesystem::path& file, const CalibratedContactLaw& law,
                            const std::string& material, const std::string& implant,
                            const ContactLawKey& key);

// the implant a law belongs to: "generic" for the built-in implant, else the insert mesh path
// as the config names it
std::string implant_identity(const Config& config);

// writes the law file atomically
void write_contact_law_file(const std::filesystem::path& file, const CalibratedContactLaw& law);

}  // namespace kneesim::models
