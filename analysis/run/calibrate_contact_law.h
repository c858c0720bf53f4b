// The calibration of the rigid insert's contact law against the deformable insert as a library
// call (after Halloran 2005): `kneesim calibrate-contact` is its shell, and every simulating
// command calls ensure_contact_law, which runs it on first use for an implant and material
// without a shipped or cached law (models/contact_law_library.h).
//
// Procedure, under the reference load case of models::make_calibration_config (the config's
// implant, material, contact.law and deformable reference mesh; everything else at its default, i.e.
// the stanmore rig and the shipped gait): one deformable cycle (or a finished deformable run;
// optionally on finer surfaces than the rigid runs', ContactCalibrationJob::reference_*),
// the rigid insert with the law as specified, and a nested golden-section search of the law
// p = K_eff g^n (engine/contact_law.h): the exponent n over log n in [0.3, 1.5] outside, the
// effective foundation modulus K_eff over log K in [0.01, 10] times modulus_search_reference inside, minimizing
// peak^2 + mean^2 of the normalized RMS frame errors over 0-30 % of the cycle
// (analysis/run/contact_calibration.h);
// the errors over 30-60 %, which the fit never saw, are the held-out judgement. A fit that ends
// at a search bound (of either parameter) is no calibration: InputError, and no law is written.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "models/config.h"
#include "models/contact_law_file.h"

namespace kneesim::run {

struct ContactCalibrationJob {
  models::Config config;                   // the config whose law is calibrated
  std::filesystem::path out;               // runs and outputs
  std::filesystem::path deformable_from;   // a finished deformable run to fit against, or ""
  std::string command;                     // the command line, for the provenance
  bool plots = true;                       // out/calibration.png
  bool quiet = false;                      // no progress lines on stderr
  double exponent = 0.0;                   // > 0: n fixed at this value, K_eff alone fitted
  // the deformable reference's surfaces (0: the config's, as the rigid runs): the built-in
  // implant's triangulation (implant.edge_length_mm) and the femur's distance-field spacing
  // (contact.sdf_spacing_mm). A stiff insert's small patch follows the 1 mm facets' ridges
  // (docs/validation.md, CFR-PEEK on finely faceted surfaces): its converged reference needs
  // finer ones, while the rigid runs keep the surfaces a user's rigid run has
  double reference_edge_length_mm = 0.0;
  double reference_sdf_spacing_mm = 0.0;
};

struct ContactCalibrationReport {
  models::CalibratedContactLaw law;        // as written to out/contact_law.toml
  nlohmann::json summary;                  // as written to out/summary.json
};

// runs the calibration; writes out/contact_law.toml, comparison.csv (the three traces),
// summary.json and calibration.png; the runs stay in out/deformable, out/rigid (as specified)
// and out/rigid_calibrated. InputError for bad input (a config that names a law, a
// --deformable-from run of other settings) and for a fit at a search bound; a failed run
// throws as run_gait_job does
ContactCalibrationReport calibrate_contact_law(const ContactCalibrationJob& job);

// the strain at which the modulus search is centred: about the stance strains g = d/h
inline constexpr double kSearchReferenceStrain = 0.01;

// the modulus [MPa] the search for exponent n is centred on: the one whose law K g^n gives the
// law as specified's pressure K_spec g at g = kSearchReferenceStrain (K_spec for n = 1)
double modulus_search_reference(double k_spec, double exponent);

// a fitted K_eff [MPa] within 5 % of a bound of the search (0.01 to 10 times `k_ref`, the
// modulus_search_reference of the fitted exponent [MPa]) is no calibration: InputError naming
// the material, the implant, the value, the range and the folder `out` the runs are kept in
void check_fit_inside_search(double k_fit, double k_ref, const std::string& material,
                             const std::string& implant, const std::filesystem::path& out);

// the same for the fitted exponent n (search 0.3 to 1.5; within 2 % of a bound)
void check_exponent_inside_search(double n_fit, const std::string& material,
                                  const std::string& implant, const std::filesystem::path& out);

// a rigid config without a law (config.contact_law_resolution.needs_calibration) gets one:
// calibrated now in a scratch folder, stored in the cache (when on), remembered by this process
// and applied to `config`; says so on stderr unless quiet. A calibration that fails becomes an
// InputError naming the implant and material and the ways out (--no-calibrate, a law file).
// Returns true when it calibrated.
bool ensure_contact_law(models::Config& config, bool quiet = false);

// the resolution of a config's law as summary.json reports it: the law, its modulus, the
// source, file, key, provenance and any warning or note
nlohmann::json describe_contact_law(const models::Config& config, double foundation_modulus_MPa);

}  // namespace kneesim::run
