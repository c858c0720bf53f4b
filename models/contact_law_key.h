// What a calibrated rigid contact law belongs to (models/contact_law_file.h,
// models/contact_law_library.h): the key under which a law is shipped, cached and checked.
//
// A law is the rigid insert's elastic foundation fitted to the deformable insert of the same
// implant and material under a reference load case (calibration_config below), so it is a
// property of
//   - the implant's geometry: the generic implant's shape parameters, or the content of an
//     imported implant's mesh files with the keys that place them (units, rotation, mirror, FE
//     axis, base plane, articular threshold);
//   - the insert material's constants (E, nu, yield, density, friction);
//   - the law's form (contact.law) and the deformable reference: every [deformable] key.
// It is not a property of the rig, the gait, the alignment or the friction override: those are
// the loading, which the calibration fixes (the default stanmore rig and the shipped gait) and
// which the law is assumed to carry over to (docs/deformable.md measures the other rig). Nor of
// the rigid path's discretization (implant.edge_length_mm, the distance field's spacing and
// band): the calibration runs at their defaults, and a coarse test mesh uses the law of the
// implant it approximates.
//
// Three FNV-1a 64-bit hashes in hex: implant, material and settings; the key is the hash of
// all three with the procedure's version. The part hashes let a refusal say what differs.
#pragma once

#include <string>
#include <vector>

namespace kneesim::models {

struct Config;

// version of the calibration procedure: a change of the fit, its windows or the reference
// load case changes every key, so no stale law is found
inline constexpr int kContactCalibrationVersion = 2;  // 2: the exponent fitted with K, the refined mesh

struct ContactLawKey {
  std::string implant;   // hex hash of the implant geometry
  std::string material;  // hex hash of the material constants
  std::string settings;  // hex hash of contact.law and the [deformable] keys
  std::string key;       // hex hash of the three and the procedure version
};

// the key of the config's implant, material and settings; InputError naming a mesh file that
// cannot be read
ContactLawKey make_contact_law_key(const Config& config);

// the deformable insert the laws are calibrated against by default (the reference mesh): the
// default [deformable] keys with these, the footprint-refined mesh on which UHMWPE's and PEEK's
// peak and stance-mean pressure on the built-in implant change by less than 5 % from the previous
// refinement (docs/validation.md, "Deformable insert mesh convergence"). kneesim
// calibrate-contact --element-mm and --set deformable.* set another.
struct ConfigSetting {
  const char* key;
  const char* value;  // as on the command line (TOML value)
};
inline constexpr ConfigSetting kContactCalibrationReferenceMesh[] = {
    {"deformable.element_size_mm", "0.5"},
    {"deformable.layers", "6"},
    {"deformable.grading", "0.15"},
    {"deformable.refine", "\"contact\""},
};

// the reference load case the law of `config` is calibrated under: the built-in defaults with
// the config's implant, material and contact.law (rigid insert, the law as specified); every
// other key at its default, so the key above describes it completely. The deformable reference:
// with `own_reference` (kneesim calibrate-contact) the config's [deformable] keys, else the
// default [deformable] keys with kContactCalibrationReferenceMesh (what a rigid config's law is
// looked up and calibrated on first use under: a rigid run does not use [deformable])
Config make_calibration_config(const Config& config, bool own_reference = false);

// the keys whose value in `config` the calibration does not use: those where
// make_calibration_config(config, true) holds another value (the load case, the solver, the
// contact settings besides the law, the rigid runs' surfaces), sorted
std::vector<std::string> calibration_unused_keys(const Config& config);

}  // namespace kneesim::models
