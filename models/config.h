// The run configuration as the user writes it (TOML, units in the key names), every field
// defaulted so `kneesim run` needs no file. models/build_model converts it to an SI Model.
//
// Loading order: defaults -> rig preset (rig.preset, from the file or --set) -> every key of
// the file -> every --set override. Each key is registered once in config.cpp with its type
// and allowed range, so unknown keys and out-of-range values are rejected with one sentence
// naming the file, key, value and range.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace kneesim::models {

struct MaterialConfig {
  std::string name = "uhmwpe";               // library name or a [materials.<name>] table
  double elastic_modulus_MPa = 685.0;        // Young's modulus [MPa]
  double poisson = 0.47;                     // [-]
  double yield_MPa = 17.0;                   // [MPa]
  double density_g_per_cm3 = 0.935;          // [g/cm^3]
  double friction = 0.07;                    // Coulomb coefficient against CoCr [-]
  double wear_factor_mm3_per_Nmm = 2.643e-10;  // Archard k [mm^3/(N mm)]
  // C of the contact-area law dh = C f(CS) ds (Abdelgaied 2011); 0: none known [-]
  double area_wear_coefficient = 0.0;
  std::string source;                        // where the values come from
  // where the wear factor comes from, and whether it is independent of the comparisons the
  // project makes (false: calibrated on, or derived from, what kneesim is judged against, so
  // wear volumes made with it are not predictions; `kneesim compare` says so). A material
  // table that sets the factor must name its source (bad input otherwise); a factor set by an
  // override without a source gets the override as its source and counts as not independent
  std::string wear_factor_source = "Pal 2008 (conventional UHMWPE against CoCr)";
  bool wear_factor_independent = true;
  // the material's own pressure dependence of its wear factor, k = k_ref (p / p_ref)^n, used by
  // the wear law "material_pressure": k_ref is wear_factor_mm3_per_Nmm, the factor at p_ref
  double wear_pressure_exponent = 0.0;        // n [-], either sign (UHMWPE's falls with p)
  double wear_reference_pressure_MPa = 10.0;  // p_ref [MPa]
  // a [materials.<name>] table of a config: the properties it did not set and took from the
  // built-in defaults (UHMWPE against CoCr), "key = value, ..."; said once when it is used
  std::string defaults_taken;
  std::string wear_pressure_source;           // the direction's citation and the magnitude's
};

// [wear]: the wear law every wear prediction uses (run's wear-rate maps, wear, compare, study
// wear trials, the diagnosis forward models); wear/wear_law.h turns it into wear::WearLawParams.
// The coefficient (k, or C of the area law) is the material's; these are the law's shape.
struct WearConfig {
  std::string law = "archard";          // archard | pressure_dependent_wear | cross_shear |
                                        // contact_area | running_in | incubation
  double cross_shear_gain = 0.0;        // g in f(CS) = 1 + g CS [-]
  double pressure_exponent = 0.0;       // alpha in (p / p_ref)^-alpha [-]
  double reference_pressure_MPa = 10.0; // p_ref [MPa]
  double running_in_excess = 0.0;       // a, initial extra wear-rate ratio [-]
  double running_in_cycles = 2e5;       // N_r [cycles]
  double incubation_cycles = 2e5;       // N_i [cycles]
  bool creep = false;                   // add creep penetration (separate from wear)
  double creep_ratio = 0.5;             // phi, saturated creep over elastic penetration [-]
  double creep_time_s = 3600.0;         // tau, creep time constant [s]
};

// the [wear] parameter keys (without "wear.") the law `law` uses; creep_ratio and creep_time_s
// belong to wear.creep = true (any law)
std::vector<std::string> wear_law_parameter_keys(const std::string& law);

// how the rigid insert's contact law of a config was found (models/contact_law_library.h);
// filled by load_config, completed by run::ensure_contact_law when it calibrates
struct ContactLawResolution {
  // "library" (shipped, models/contact_laws), "cache" (calibrated on an earlier first use),
  // "calibrated" (calibrated by this process), "law_file" (contact.law_file),
  // "modulus" (contact.foundation_modulus_MPa), "specified" (contact.calibration = "off"),
  // "unused" (deformable insert), "" (none found yet: needs_calibration)
  std::string source;
  std::string file;                // the law file used, "" when none
  std::string key;                 // the config's calibration key (models/contact_law_key.h)
  bool needs_calibration = false;  // no law found for the key: calibrate before a rigid run
  std::string note;                // a stale law for the same implant path, when found
  std::string warning;             // one line: the law as specified and how far off it runs
  // the law file's provenance: key -> value in TOML syntax
  std::vector<std::pair<std::string, std::string>> provenance;
};

struct Config {
  std::filesystem::path file;  // the config file ("" for built-in defaults)

  // [implant]
  std::string implant_kind = "generic";  // "generic" | "mesh"
  double edge_length_mm = 1.0;           // insert surface resolution [mm]
  // [implant.generic]
  double femur_distal_radius_mm = 38.0, femur_posterior_radius_mm = 22.0;
  double femur_coronal_radius_mm = 20.0, condyle_width_mm = 20.0, condyle_spacing_mm = 44.0;
  double insert_sagittal_radius_mm = 70.0, insert_coronal_radius_mm = 25.0;
  double insert_thickness_mm = 8.0, insert_ap_depth_mm = 46.0, insert_ml_width_mm = 72.0;
  // [implant.mesh]
  std::string femur_mesh, insert_mesh;   // paths, ${KNEESIM_DATA} expanded
  std::string mesh_units = "m";          // "m" | "mm"
  std::array<double, 3> mesh_rotation_deg{0, 0, 0};  // XYZ rotation into the project frame
  bool mesh_left_knee = false;           // mirror z after rotation
  std::array<double, 3> femur_origin_mm{0, 0, 0};  // FE axis centre, mesh frame (after rotation)
  double insert_base_y_mm = 0.0;         // insert base plane height, project frame
  double articular_min_normal_y = 0.35;  // insert faces steeper than this are not articular
  bool insert_closed = true;             // require a closed insert mesh
  double femur_refine_mm = 0.0;          // smooth refinement of the femur to this median edge
                                         // (models/smooth_refine.h); 0: the file's triangles

  // [material]
  MaterialConfig material;
  std::map<std::string, MaterialConfig> user_materials;  // [materials.<name>]

  // [wear]
  WearConfig wear;

  // [contact]
  std::string contact_law = "nonlinear";   // "linear" | "nonlinear"
  double contact_law_exponent = 1.0;       // n of p = K g^n (engine/contact_law.h)
  double contact_damping_ratio = 0.3;      // of the stiffest contact mode [-]
  double sdf_spacing_mm = 0.4;             // femoral distance-field node spacing [mm]
  double sdf_band_mm = 1.5;                // exact band of the field [mm]
  // eps of the regularized Coulomb law [mm/s], far below the stance slip speeds (tens of
  // mm/s): the friction is integrated implicitly and capped at Coulomb's bound
  // (engine/implicit_friction.h), so any eps is stable; 0.1 mm/s is within 0.1 % of
  // 0.03 mm/s in 5 Mc wear (docs/validation.md#friction-regularization)
  double friction_regularization_mm_per_s = 0.1;
  double runaway_fraction = 0.5;           // max penetration / layer thickness [-]
  double friction_override = -1.0;         // >= 0 replaces the material's friction [-]
  // a calibrated law file (models/contact_law_file.h, kneesim calibrate-contact): sets
  // contact_law and contact_foundation_modulus_MPa; "" for the law as specified
  std::string contact_law_file;
  double contact_foundation_modulus_MPa = 0.0;  // > 0 replaces the material's K [MPa]
  // "first_use": the law calibrated for the implant and material (shipped or cached), else
  // calibrated now against the deformable insert and cached; "auto": the calibrated law when one
  // is found, else the law as specified with a warning; "off": the law as specified, with a
  // warning (--no-calibrate)
  std::string contact_calibration = "first_use";
  ContactLawResolution contact_law_resolution;

  // [rig]
  std::string rig_preset = "stanmore";     // "stanmore" | "materials_study" | "displacement" | "iso"
  std::array<std::string, 6> femur_dofs;   // mode per DOF ap,is,ml,vv,ie,fe (preset)
  std::array<std::string, 6> tibia_dofs;
  double axial_offset_mm = 5.0;            // medial offset of the axial load line [mm]
  double tibia_pivot_medial_mm = 5.0;      // medial offset of the tibial VV (and IE) axis [mm]
  double femur_vv_deg = 0.0;               // VV alignment of the femoral component (locked
                                           // femoral VV), + varus [deg]
  // generalized masses and dampers of the carriage DOFs, per DOF and the same on either
  // carriage: this project's assumptions (the papers give none), small enough that the rig is
  // quasi-static (halving or doubling each moves the ranges of motion by under 2 %,
  // docs/validation.md#carriage-masses); the axial mass sets the time step
  double ap_mass_kg = 0.06, is_mass_kg = 8.0, ml_mass_kg = 0.25;          // [kg]
  double vv_inertia_kgm2 = 0.01, ie_inertia_kgm2 = 3e-5, fe_inertia_kgm2 = 0.01;  // [kg m^2]
  double ap_damping_Ns_per_m = 1.0, ml_damping_Ns_per_m = 5.0, is_damping_Ns_per_m = 0.0;
  double ie_damping_Nms_per_rad = 0.003, vv_damping_Nms_per_rad = 0.01;
  // restraint (spring-gap, physics.md section 2); preset-dependent defaults
  std::string restraint = "springs";       // "springs" (four AP springs) | "linear" | "none"
  double gap_mm = 3.0;
  double k_anterior_N_per_mm = 4.75, k_posterior_N_per_mm = 22.18;
  double k_inside_N_per_mm = 0.0;
  double spring_arm_mm = 35.0;             // lever arm of the AP springs from the IE axis [mm]
  double ie_gap_deg = 0.0;
  double k_ie_inside_Nm_per_deg = 0.0, k_ie_Nm_per_deg = 0.0;  // rotational restraint
  // [rig.alignment]: how the implant sits in the rig, relative to the implant's own reference
  // (0 = as built: the femoral FE axis through F's origin, the tibial IE axis at the rig's
  // pivot, no rotations), so that any implant keeps Pal 2008's SDs (physics.md section 8)
  double femur_fe_axis_ap_mm = 0.0;  // FE axis relative to the femoral component, + anterior [mm]
  double femur_fe_axis_is_mm = 0.0;  // FE axis relative to the femoral component, + superior [mm]
  double tibia_ie_axis_ap_mm = 0.0;  // IE (and VV) axis relative to the insert, + anterior [mm]
  double tibia_ie_axis_ml_mm = 0.0;  // IE (and VV) axis relative to the rig pivot, + lateral [mm]
  double femur_fe_deg = 0.0;  // femoral component on its carriage about +z, + flexion [deg]
  double femur_ie_deg = 0.0;  // femoral component about +y (+ = external tibial rotation) [deg]
  double insert_tilt_deg = 0.0;  // insert about +z through T's origin, + posterior slope [deg]

  // [gait]
  std::string gait_file;                   // waveform file ("" = shipped ISO 14243-1 approx.)
  std::string kinematics_file;             // measured kinematics for displacement mode
  double period_s = 1.0;
  double ap_sign = 1.0, ie_sign = 1.0;     // sign conventions of the file's AP and IE channels
  double axial_force_scale = 1.0, ap_force_scale = 1.0, ie_torque_scale = 1.0;
  // factors on the prescribed AP displacement and IE rotation waveforms (displacement control)
  double ap_displacement_scale = 1.0, ie_rotation_scale = 1.0;
  // varus-valgus torque on the tibial carriage (+ varus, loads the medial condyle), added to a
  // free tibial VV DOF (which becomes force-driven): (arm + stance arm x a stance-phase shape)
  // x axial force: the axial load line moved medially, constantly or following the stance
  // phase (models/gait_assembly.h)
  double vv_torque_axial_arm_mm = 0.0;     // [mm]
  double vv_torque_stance_arm_mm = 0.0;    // [mm]

  // [gait.measured]: a measured load table drives rig channels (loads/iso14243/measured_loads.h)
  std::string measured_file;               // table (CSV); "" = none
  std::string measured_time_column;        // "" = first column
  std::string measured_time_unit;          // "" = from the header; "s", "ms", "pct"
  std::vector<double> measured_window;     // one gait cycle [start, end] in time-column units
  std::string measured_force_unit, measured_moment_unit;  // units of bare headers
  std::string measured_angle_unit, measured_length_unit;
  std::vector<std::string> measured_channels;  // "target = expression": rig channels
  std::vector<std::string> measured_compare;   // measured outputs for comparison (diagnose)

  // delays of the AP force and IE torque waveforms [% of the cycle] (load-timing candidates of
  // the kinematics diagnosis, run forward)
  double ap_force_shift_pct = 0.0, ie_torque_shift_pct = 0.0;

  // insert = "rigid" (elastic foundation on the articular elements) | "deformable" (hex8
  // solid meshed from the insert, engine/insert_solid.h)
  std::string insert_kind = "rigid";
  // [deformable]: the deformable insert's mesh, time step and material model
  // the mesh (models/deformable_insert.h says how the keys combine)
  double deformable_element_size_mm = 1.0;  // grid spacing over the footprint [mm] (in the
                                            // refined zone; with elements_across_contact its
                                            // upper bound)
  int deformable_elements_across_contact = 0;  // spacing = patch width / this; 0: element_size
  double deformable_min_element_size_mm = 0.1; // lower bound of that spacing [mm]
  int deformable_layers = 4;                // elements through the thickness (0: from the
                                            // refined spacing, growing by 1.5 per layer)
  double deformable_grading = 0.5;          // top / bottom layer thickness [-] (layers > 0)
  // refinement of the footprint grid where the gait cycle's contact occurs
  // (models/contact_footprint.h): "contact" | "none" (uniform)
  std::string deformable_refine = "none";
  double deformable_outer_element_size_mm = 3.0;  // spacing away from the contact zone [mm]
  double deformable_refine_margin_mm = 3.0;  // zone = rigid cycle's contact + this margin [mm]
  double deformable_dt_us = 20.0;           // time step reached by mass scaling [us]; 0: none
  double deformable_damping_per_s = 1000.0; // mass-proportional damping [1/s]
  std::string deformable_material = "elastoplastic";  // "elastoplastic" (J2) | "elastic"
  double deformable_hardening_MPa = 50.0;   // isotropic hardening slope H [MPa]
  double deformable_yield_cap_MPa = 33.0;   // yield stress ceiling [MPa] (UHMWPE, physics.md)

  // [solver]
  std::string integrator = "central_difference";  // "central_difference" | "cvode"
  std::string rig_coupling = "partitioned";        // "partitioned" | "coupled"
  double dt_safety = 0.8;                  // fraction of the estimated stability limit [-]
  int threads = 1;                         // threads of one run (0: automatic)
  int cycles = 2;                          // gait cycles; outputs come from the last

  // [conditions.<name>]: named variants of this config for multi-condition studies (knee-wear
  // diagnosis): each is a list of "key=value" overrides, e.g.
  //   [conditions.low_ie]
  //   set = ["gait.ie_torque_scale=0.5"]
  std::map<std::string, std::vector<std::string>> conditions;

  // [output]
  std::vector<double> map_pcts{0, 13, 24, 45, 60, 80};  // gait % of the pressure maps
  std::string measured_kinematics;        // optional overlay for the kinematics plot
};

// `key=value` from the command line (value in TOML syntax; bare words are strings)
struct Override {
  std::string key, value;
};

// loads a config file ("" for pure defaults) and applies overrides; throws InputError
Config load_config(const std::filesystem::path& file, const std::vector<Override>& overrides);

// parses "key=value" into an Override; throws InputError naming the text
Override parse_override(const std::string& text);

// a number key's value in `config` and its allowed range; nullopt when `key` is not a number
// key (unknown, text, list); used by the studies to vary any key by name
struct NumberKey {
  double value = 0.0, lo = 0.0, hi = 0.0;
};
std::optional<NumberKey> find_number_key(const Config& config, const std::string& key);

// one registered key as the configuration reference lists it (kneesim config --reference,
// docs/config-reference.md): generated from the registry that loads configs, so it cannot drift
struct KeyReference {
  std::string key;            // dotted, e.g. "contact.law"
  std::string type;           // number, integer, sign, text, choice, boolean, list ...
  std::string allowed;        // the allowed values, as the error message states them
  std::string meaning;        // one line
  std::string default_value;  // TOML syntax, under the default rig preset (stanmore)
  std::vector<std::pair<std::string, std::string>> preset_defaults;  // presets that differ
};
std::vector<KeyReference> config_reference();

// ${KNEESIM_DATA} and ${KNEESIM_SOURCE} expansion, relative paths resolved against the config
std::filesystem::path resolve_path(const Config& config, const std::string& path);

// the materials library shipped in models/materials.toml plus the config's own materials
MaterialConfig find_material(const Config& config, const std::string& name);
std::vector<std::string> library_material_names();

}  // namespace kneesim::models
