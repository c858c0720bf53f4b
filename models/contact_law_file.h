// A calibrated elastic-foundation law for the rigid insert (issue 11 item 6), written by
// `kneesim calibrate-contact` and named by a config as contact.law_file. The file holds the
// law the rigid path uses (the nonlinear or linear foundation law of physics.md section 4) with
// an effective foundation modulus fitted against the deformable insert, and the material and
// implant it was fitted for: a config of another material or implant cannot use it.
//
//   [calibrated_contact]
//   material = "uhmwpe"              # the config's material.name
//   implant = "generic"              # "generic" or the insert mesh path as the config names it
//   law = "nonlinear"                # contact.law
//   foundation_modulus_MPa = 812.3   # K_eff, replaces K = (1-nu)E/((1+nu)(1-2nu))
//   specified_modulus_MPa = 4170.0   # K of the material, for the record
//   fitted_on = "..."                # what it was fitted on, for the record
//
// Why an effective modulus and not a tabulated law: the rigid path's pressure at an element is
// a function of its own penetration only; what the deformable insert adds is load spreading
// (a neighbour's penetration), which no pointwise law can carry. A single stiffness factor is
// the one degree of freedom a pointwise law has to trade peak pressure against contact area;
// a shape change (exponent or table) was not fitted because the stance peak and mean pressure
// errors it would have to reduce are already within the fitted modulus' reach or not at all
// (docs/deformable.md gives the measured errors).
#pragma once

#include <filesystem>
#include <string>

namespace kneesim::models {

struct Config;

struct CalibratedContactLaw {
  std::string material;              // material name
  std::string implant;               // "generic" or the insert mesh path
  std::string law = "nonlinear";     // "linear" | "nonlinear"
  double foundation_modulus_MPa = 0.0;   // K_eff [MPa]
  double specified_modulus_MPa = 0.0;    // K of the material [MPa]
  std::string fitted_on;             // description
};

// reads and checks a law file; InputError (one sentence naming the file, the key, the value
// and what is allowed) for a missing or malformed file, a value out of range, or a law fitted
// for another material or implant than `material` / `implant`
CalibratedContactLaw read_contact_law_file(const std::filesystem::path& file,
                                           const std::string& material,
                                           const std::string& implant);

// the implant a law belongs to: "generic" for the built-in implant, else the insert mesh path
// as the config names it
std::string implant_identity(const Config& config);

// writes the law file atomically
void write_contact_law_file(const std::filesystem::path& file, const CalibratedContactLaw& law);

}  // namespace kneesim::models
