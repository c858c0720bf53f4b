// The config's key table: every key of Config registered with its type, allowed range and
// one-line meaning (docs/config-reference.md is generated from it), and the rig presets'
// defaults with their sources.
#include <array>
#include <string>
#include <vector>

#include "models/config_registry.h"

namespace kneesim::models::config_detail {

const std::vector<std::string> kDofModes = {"locked", "free", "prescribed", "force"};
const std::vector<std::string> kDofKeys = {"ap", "is", "ml", "vv", "ie", "fe"};

void register_material(Registry& r, const std::string& prefix, MaterialConfig& m) {
  r.number(prefix + "elastic_modulus_MPa", m.elastic_modulus_MPa, 1.0, 1e6,
    "Young's modulus of the insert material");
  r.number(prefix + "poisson", m.poisson, 0.0, 0.49,
    "Poisson's ratio of the insert material");
  r.number(prefix + "yield_MPa", m.yield_MPa, 0.0, 1e4,
    "yield stress of the insert material (deformable insert, particles)");
  r.number(prefix + "density_g_per_cm3", m.density_g_per_cm3, 0.1, 30.0,
    "density (gravimetric wear = volume x density)");
  r.number(prefix + "friction", m.friction, 0.0, 1.0,
    "Coulomb friction coefficient against the CoCr femoral component");
  r.number(prefix + "wear_factor_mm3_per_Nmm", m.wear_factor_mm3_per_Nmm, 0.0, 1e-3,
    "wear factor k of the wear law (Archard: dh = k p ds sqrt(1 + 3 mu^2))");
  r.number(prefix + "area_wear_coefficient", m.area_wear_coefficient, 0.0, 1e-3,
    "coefficient C of the contact-area wear law dh = C f(CS) ds (0: none known)");
  r.text(prefix + "source", m.source,
    "where the material's values come from (reported in outputs)");
  r.text(prefix + "wear_factor_source", m.wear_factor_source,
    "where the wear factor comes from (a citation; required wherever a material table sets the factor)");
  r.flag(prefix + "wear_factor_independent", m.wear_factor_independent,
    "the wear factor is independent of what kneesim is compared with (false: its wear volumes are not predictions)");
  r.number(prefix + "wear_pressure_exponent", m.wear_pressure_exponent, -3.0, 3.0,
    "n of the material's pressure-dependent wear factor k = k_ref (p / p_ref)^n (wear law material_pressure)");
  r.number(prefix + "wear_reference_pressure_MPa", m.wear_reference_pressure_MPa, 0.01, 1000.0,
    "p_ref at which wear_factor_mm3_per_Nmm applies (wear law material_pressure)");
  r.text(prefix + "wear_pressure_source", m.wear_pressure_source,
    "where the direction and magnitude of wear_pressure_exponent come from");
}

Registry make_registry(Config& c) {
  Registry r;
  r.choice("implant.kind", c.implant_kind, {"generic", "mesh"},
    "the built-in parametric implant (\"generic\") or your own meshes (\"mesh\")");
  r.number("implant.edge_length_mm", c.edge_length_mm, 0.2, 5.0,
    "target edge length of the rigid insert's articular elements");
  r.number("implant.generic.femur_distal_radius_mm", c.femur_distal_radius_mm, 15, 80,
    "generic implant: femoral condyle sagittal radius, distal arc");
  r.number("implant.generic.femur_posterior_radius_mm", c.femur_posterior_radius_mm, 10, 60,
    "generic implant: femoral condyle sagittal radius, posterior arc");
  r.number("implant.generic.femur_coronal_radius_mm", c.femur_coronal_radius_mm, 5, 1000,
    "generic implant: femoral condyle coronal radius");
  r.number("implant.generic.condyle_width_mm", c.condyle_width_mm, 8, 40,
    "generic implant: width of each femoral condyle");
  r.number("implant.generic.condyle_spacing_mm", c.condyle_spacing_mm, 20, 70,
    "generic implant: medial-lateral distance between condyle centres");
  r.number("implant.generic.insert_sagittal_radius_mm", c.insert_sagittal_radius_mm, 20, 1000,
    "generic implant: insert dish sagittal radius");
  r.number("implant.generic.insert_coronal_radius_mm", c.insert_coronal_radius_mm, 5, 1000,
    "generic implant: insert dish coronal radius");
  r.number("implant.generic.insert_thickness_mm", c.insert_thickness_mm, 4, 30,
    "generic implant: insert thickness under the dwell points");
  r.number("implant.generic.insert_ap_depth_mm", c.insert_ap_depth_mm, 25, 80,
    "generic implant: insert anterior-posterior depth");
  r.number("implant.generic.insert_ml_width_mm", c.insert_ml_width_mm, 40, 100,
    "generic implant: insert medial-lateral width");
  r.text("implant.mesh.femur", c.femur_mesh,
    "femoral component mesh (STL, OBJ, PLY); ${KNEESIM_DATA} is expanded, relative to the config");
  r.text("implant.mesh.insert", c.insert_mesh,
    "tibial insert mesh (STL, OBJ, PLY), closed unless insert_closed = false");
  r.choice("implant.mesh.units", c.mesh_units, {"m", "mm"},
    "length unit of both mesh files");
  r.vec3("implant.mesh.rotation_deg", c.mesh_rotation_deg,
    "rotation about x, y, z (applied in that order) from the mesh frame into the project frame (+x anterior, +y superior, +z lateral)");
  r.flag("implant.mesh.left_knee", c.mesh_left_knee,
    "mirror z after rotation (left knees)");
  r.vec3("implant.mesh.femur_origin_mm", c.femur_origin_mm,
    "flexion-extension axis (along z) through the femoral component, in the rotated mesh frame; the default is the files' origin (kneesim implant check fits the distal condylar arcs' centre)");
  r.number("implant.mesh.insert_base_y_mm", c.insert_base_y_mm, -100, 100,
    "height of the insert's base plane in the rotated frame (layer thickness is measured from it)");
  r.number("implant.mesh.articular_min_normal_y", c.articular_min_normal_y, -1, 1,
    "insert faces whose normal's y component is below this are not articular");
  r.flag("implant.mesh.insert_closed", c.insert_closed,
    "require a closed (watertight) insert mesh, needed for the volume loss");
  r.number("implant.mesh.femur_refine_mm", c.femur_refine_mm, 0.0, 5.0,
    "refine the femoral mesh on a smooth surface through its vertices until the median edge is at most this (0: the file's triangles; validation.md, DM implant)");

  r.text("material.name", c.material.name,
    "insert material: a library name (models/materials.toml) or a [materials.<name>] table");
  register_material(r, "material.", c.material);

  r.choice("wear.law", c.wear.law,
    {"archard", "pressure_dependent_wear", "material_pressure", "cross_shear", "contact_area",
     "running_in", "incubation"},
    "wear law of every wear prediction (theory: wear laws); its coefficient is the material's "
    "(material_pressure: pressure_dependent_wear with the material's own exponent and p_ref)");
  r.number("wear.cross_shear_gain", c.wear.cross_shear_gain, 0.0, 1000.0,
    "cross_shear, contact_area: g in the cross-shear factor f(CS) = 1 + g CS");
  r.number("wear.pressure_exponent", c.wear.pressure_exponent, -3.0, 4.0,
    "pressure_dependent_wear, cross_shear: alpha in the pressure factor (p / p_ref)^-alpha");
  r.number("wear.reference_pressure_MPa", c.wear.reference_pressure_MPa, 0.01, 1000.0,
    "pressure_dependent_wear, cross_shear: p_ref of the pressure factor");
  r.number("wear.running_in_excess", c.wear.running_in_excess, 0.0, 1e4,
    "running_in: initial extra wear-rate ratio a in 1 + a exp(-N / N_r)");
  r.number("wear.running_in_cycles", c.wear.running_in_cycles, 1.0, 1e9,
    "running_in: decay constant N_r");
  r.number("wear.incubation_cycles", c.wear.incubation_cycles, 1.0, 1e9,
    "incubation: time constant N_i in 1 - exp(-N / N_i)");
  r.flag("wear.creep", c.wear.creep,
    "add creep penetration phi d_el (1 - exp(-t / tau)) to the reported depth (no volume loss)");
  r.number("wear.creep_ratio", c.wear.creep_ratio, 0.0, 100.0,
    "creep: saturated creep over the cycle-mean elastic penetration, phi");
  r.number("wear.creep_time_s", c.wear.creep_time_s, 1e-3, 1e12,
    "creep: time constant tau of the creep penetration (loaded test time)");

  r.choice("contact.law", c.contact_law, {"linear", "nonlinear"},
    "rigid insert's elastic-foundation law: p = K g^n with g = -ln(1 - d/h) (nonlinear) or g = d/h (linear)");
  r.number("contact.law_exponent", c.contact_law_exponent, 0.2, 2.0,
    "exponent n of the rigid insert's law p = K g^n (1: the classical laws; a calibrated law sets its fitted n)");
  r.number("contact.damping_ratio", c.contact_damping_ratio, 0.0, 1.0,
    "contact damping as a fraction of critical for the stiffest contact mode");
  r.number("contact.sdf_spacing_mm", c.sdf_spacing_mm, 0.05, 2.0,
    "node spacing of the femoral signed distance field");
  r.number("contact.sdf_band_mm", c.sdf_band_mm, 0.5, 10.0,
    "half-width of the distance field's exact band around the femoral surface");
  r.number("contact.friction_regularization_mm_per_s", c.friction_regularization_mm_per_s, 1e-4,
           100.0,
    "slip speed eps of the regularized Coulomb law t = -mu p v / sqrt(v^2 + eps^2)");
  r.number("contact.runaway_fraction", c.runaway_fraction, 0.01, 0.95,
    "a run stops as runaway when penetration exceeds this fraction of the layer thickness");
  r.number("contact.friction", c.friction_override, 0.0, 1.0,
    "friction coefficient replacing the material's (-1: the material's)");
  r.text("contact.law_file", c.contact_law_file,
    "a calibrated contact law (kneesim calibrate-contact) replacing contact.law and the foundation modulus");
  r.choice("contact.calibration", c.contact_calibration, {"first_use", "auto", "off"},
    "rigid insert: first_use: the law calibrated against the deformable insert for the implant and material (shipped in models/contact_laws or cached), else calibrated now (one deformable gait cycle on the reference mesh, minutes; cached); auto: the calibrated law when one is found, else the law as specified with a warning; off: the law as specified, with a warning (--no-calibrate)");
  r.number("contact.foundation_modulus_MPa", c.contact_foundation_modulus_MPa, 0.0, 1e6,
    "foundation modulus replacing K = (1-nu)E/((1+nu)(1-2nu)) (0: the calibrated law's K_eff, contact.calibration, or the material's K)");

  r.choice("rig.preset", c.rig_preset, {"stanmore", "materials_study", "displacement", "iso"},
    "simulator rig: DOFs, restraint and offsets (rig presets in the user guide)");
  for (int i = 0; i < 6; ++i) {
    r.choice("rig.femur." + kDofKeys[i], c.femur_dofs[i], kDofModes,
      "mode of the femoral carriage DOF: locked, free, prescribed (waveform) or force (waveform force plus restraint)");
    r.choice("rig.tibia." + kDofKeys[i], c.tibia_dofs[i], kDofModes,
      "mode of the tibial carriage DOF: locked, free, prescribed (waveform) or force (waveform force plus restraint)");
  }
  r.number("rig.axial_offset_mm", c.axial_offset_mm, -30, 30,
    "medial offset of the axial load line");
  r.number("rig.tibia_pivot_medial_mm", c.tibia_pivot_medial_mm, -30, 30,
    "medial offset of the tibial varus-valgus and internal-external axis");
  r.number("rig.femur_vv_deg", c.femur_vv_deg, -15, 15,
    "varus-valgus alignment of the femoral component with locked femoral VV, + varus");
  r.number("rig.ap_mass_kg", c.ap_mass_kg, 1e-4, 1000,
    "carriage mass in anterior-posterior translation (a light DOF, integrated implicitly; project assumption)");
  r.number("rig.is_mass_kg", c.is_mass_kg, 0.01, 1000,
    "carriage mass in inferior-superior translation (the femur's axial DOF; sets the time step; project assumption)");
  r.number("rig.ml_mass_kg", c.ml_mass_kg, 1e-3, 1000,
    "carriage mass in medial-lateral translation (project assumption)");
  r.number("rig.vv_inertia_kgm2", c.vv_inertia_kgm2, 1e-5, 100,
    "carriage rotary inertia in varus-valgus (project assumption)");
  r.number("rig.ie_inertia_kgm2", c.ie_inertia_kgm2, 1e-8, 100,
    "carriage rotary inertia in internal-external rotation (a light DOF, integrated implicitly; project assumption)");
  r.number("rig.fe_inertia_kgm2", c.fe_inertia_kgm2, 1e-5, 100,
    "carriage rotary inertia in flexion-extension (prescribed in every preset; project assumption)");
  r.number("rig.ap_damping_Ns_per_m", c.ap_damping_Ns_per_m, 0, 1e5,
    "carriage damper on anterior-posterior translation");
  r.number("rig.ml_damping_Ns_per_m", c.ml_damping_Ns_per_m, 0, 1e5,
    "carriage damper on medial-lateral translation");
  r.number("rig.is_damping_Ns_per_m", c.is_damping_Ns_per_m, 0, 1e5,
    "carriage damper on inferior-superior translation");
  r.number("rig.ie_damping_Nms_per_rad", c.ie_damping_Nms_per_rad, 0, 1e3,
    "carriage damper on internal-external (and flexion-extension) rotation");
  r.number("rig.vv_damping_Nms_per_rad", c.vv_damping_Nms_per_rad, 0, 1e3,
    "carriage damper on varus-valgus rotation");
  r.choice("rig.restraint.kind", c.restraint, {"springs", "linear", "none"},
    "soft-tissue restraint: four AP springs at +-spring_arm (\"springs\"), AP and IE spring-gap (\"linear\"), or none");
  r.number("rig.restraint.gap_mm", c.gap_mm, 0, 20,
    "free AP play each side before the springs engage");
  r.number("rig.restraint.k_anterior_N_per_mm", c.k_anterior_N_per_mm, 0, 1e4,
    "spring stiffness beyond the gap, anterior tibial displacement");
  r.number("rig.restraint.k_posterior_N_per_mm", c.k_posterior_N_per_mm, 0, 1e4,
    "spring stiffness beyond the gap, posterior tibial displacement");
  r.number("rig.restraint.k_inside_N_per_mm", c.k_inside_N_per_mm, 0, 1e4,
    "AP stiffness inside the gap");
  r.number("rig.restraint.spring_arm_mm", c.spring_arm_mm, 0, 200,
    "lever arm of the four AP springs from the IE axis (\"springs\")");
  r.number("rig.restraint.ie_gap_deg", c.ie_gap_deg, 0, 45,
    "free IE play each side before the rotational spring engages (\"linear\")");
  r.number("rig.restraint.k_ie_inside_Nm_per_deg", c.k_ie_inside_Nm_per_deg, 0, 100,
    "IE stiffness inside the IE gap (\"linear\")");
  r.number("rig.restraint.k_ie_Nm_per_deg", c.k_ie_Nm_per_deg, 0, 100,
    "IE stiffness beyond the IE gap (\"linear\")");
  r.number("rig.alignment.femur_fe_axis_ap_mm", c.femur_fe_axis_ap_mm, -20, 20,
    "FE axis relative to the femoral component, + anterior (Pal 2008 variable)");
  r.number("rig.alignment.femur_fe_axis_is_mm", c.femur_fe_axis_is_mm, -20, 20,
    "FE axis relative to the femoral component, + superior (Pal 2008 variable)");
  r.number("rig.alignment.tibia_ie_axis_ap_mm", c.tibia_ie_axis_ap_mm, -20, 20,
    "tibial IE and VV axis relative to the insert, + anterior (Pal 2008 variable)");
  r.number("rig.alignment.tibia_ie_axis_ml_mm", c.tibia_ie_axis_ml_mm, -20, 20,
    "tibial IE and VV axis relative to the rig pivot, + lateral (Pal 2008 variable)");
  r.number("rig.alignment.femur_fe_deg", c.femur_fe_deg, -15, 15,
    "femoral component turned on its carriage about z, + flexion (Pal 2008 variable)");
  r.number("rig.alignment.femur_ie_deg", c.femur_ie_deg, -15, 15,
    "femoral component turned on its carriage about y (Pal 2008 variable)");
  r.number("rig.alignment.insert_tilt_deg", c.insert_tilt_deg, -15, 15,
    "insert turned about z through its base centre, + posterior slope (Pal 2008 variable)");

  r.text("gait.file", c.gait_file,
    "gait waveform (CSV table or key points; empty: the shipped approximate ISO 14243-1, or 14243-3 for displacement)");
  r.text("gait.kinematics_file", c.kinematics_file,
    "measured kinematics prescribed in displacement mode (CSV gait_pct, ap_mm, ie_deg, or .sto)");
  r.number("gait.period_s", c.period_s, 0.1, 100,
    "duration of one gait cycle");
  r.sign("gait.ap_sign", c.ap_sign,
    "sign convention of the waveform's AP channel");
  r.sign("gait.ie_sign", c.ie_sign,
    "sign convention of the waveform's IE channel");
  r.number("gait.axial_force_scale", c.axial_force_scale, 0, 10,
    "factor on the axial force waveform");
  r.number("gait.ap_force_scale", c.ap_force_scale, 0, 10,
    "factor on the AP force waveform");
  r.number("gait.ie_torque_scale", c.ie_torque_scale, 0, 10,
    "factor on the IE torque waveform");
  r.number("gait.ap_displacement_scale", c.ap_displacement_scale, 0, 10,
    "factor on the prescribed AP displacement waveform (displacement control)");
  r.number("gait.ie_rotation_scale", c.ie_rotation_scale, 0, 10,
    "factor on the prescribed IE rotation waveform (displacement control)");
  r.number("gait.vv_torque_axial_arm_mm", c.vv_torque_axial_arm_mm, -50, 50,
    "tibial VV torque = arm x axial force (the load line moved medially), + varus");
  r.number("gait.vv_torque_stance_arm_mm", c.vv_torque_stance_arm_mm, -50, 50,
    "tibial VV torque = arm x stance shape x axial force (zero in swing), + varus");
  r.text("gait.measured.file", c.measured_file,
    "measured load table (CSV) driving rig channels over one gait cycle");
  r.text("gait.measured.time_column", c.measured_time_column,
    "time column of the measured table (empty: the first)");
  r.choice("gait.measured.time_unit", c.measured_time_unit, {"", "s", "ms", "pct"},
    "unit of the time column (empty: from the header)");
  r.list("gait.measured.window", c.measured_window, -1e6, 1e6,
    "[start, end] of one gait cycle from heel strike, in the time column's unit");
  r.text("gait.measured.force_unit", c.measured_force_unit,
    "unit of force columns whose header carries none (N, kN, lbf)");
  r.text("gait.measured.moment_unit", c.measured_moment_unit,
    "unit of moment columns whose header carries none (Nm, Nmm, lbf*in)");
  r.text("gait.measured.angle_unit", c.measured_angle_unit,
    "unit of angle columns whose header carries none (deg, rad)");
  r.text("gait.measured.length_unit", c.measured_length_unit,
    "unit of length columns whose header carries none (mm, m, cm, in)");
  r.strings("gait.measured.channels", c.measured_channels,
    "\"target = expression\": weighted column sums driving rig channels (flexion_deg, axial_force_N, ...)");
  r.strings("gait.measured.compare", c.measured_compare,
    "measured outputs compared by kneesim diagnose forces (e.g. medial_force_N)");
  r.number("gait.ap_force_shift_pct", c.ap_force_shift_pct, -50, 50,
    "delay of the AP force waveform, % of the cycle");
  r.number("gait.ie_torque_shift_pct", c.ie_torque_shift_pct, -50, 50,
    "delay of the IE torque waveform, % of the cycle");

  r.choice("insert", c.insert_kind, {"rigid", "deformable"},
    "rigid insert with elastic-foundation contact, or deformable hex8 solid");
  r.number("deformable.element_size_mm", c.deformable_element_size_mm, 0.05, 10.0,
    "deformable insert: grid spacing over the footprint (in the refined zone); with elements_across_contact > 0 its upper bound");
  r.integer("deformable.elements_across_contact", c.deformable_elements_across_contact, 0, 100,
    "deformable insert: refined spacing per direction = the narrowest contact patch width of a rigid cycle / this (0: element_size_mm)");
  r.number("deformable.min_element_size_mm", c.deformable_min_element_size_mm, 0.02, 10.0,
    "deformable insert: lower bound of the spacing set by elements_across_contact");
  r.integer("deformable.layers", c.deformable_layers, 0, 40,
    "deformable insert: elements through the thickness (0: top layer as thick as the finest spacing, the fewest layers growing by at most 1.5 per layer)");
  r.number("deformable.grading", c.deformable_grading, 0.01, 20.0,
    "deformable insert: top / bottom layer thickness ratio (layers > 0)");
  r.choice("deformable.refine", c.deformable_refine, {"contact", "none"},
    "deformable insert: footprint grid refined to element_size_mm where the gait cycle's contact occurs (a rigid cycle finds it), or uniform");
  r.number("deformable.outer_element_size_mm", c.deformable_outer_element_size_mm, 0.2, 10.0,
    "deformable insert with refine = contact: grid spacing away from the contact zone");
  r.number("deformable.refine_margin_mm", c.deformable_refine_margin_mm, 0.0, 20.0,
    "deformable insert with refine = contact: margin around the rigid cycle's contact footprint");
  r.number("deformable.dt_us", c.deformable_dt_us, 0.0, 1000.0,
    "deformable insert: time step reached by mass scaling (0: none)");
  r.number("deformable.damping_per_s", c.deformable_damping_per_s, 0.0, 1e5,
    "deformable insert: mass-proportional damping");
  r.choice("deformable.material", c.deformable_material, {"elastoplastic", "elastic"},
    "deformable insert: J2 elastoplastic or linear elastic");
  r.number("deformable.hardening_MPa", c.deformable_hardening_MPa, 0.0, 1e5,
    "deformable insert: isotropic hardening slope");
  r.number("deformable.yield_cap_MPa", c.deformable_yield_cap_MPa, 0.0, 1e4,
    "deformable insert: yield stress ceiling");

  r.choice("solver.integrator", c.integrator, {"central_difference", "cvode"},
    "explicit central difference, or SUNDIALS CVODE as a reference");
  r.choice("solver.rig_coupling", c.rig_coupling, {"partitioned", "coupled"},
    "central difference: the light AP/IE DOFs implicit alone, or implicit in the contact's "
    "stiffness to every moved DOF (validation.md, Rig step)");
  r.number("solver.dt_safety", c.dt_safety, 0.05, 1.0,
    "time step as a fraction of the estimated stability limit");
  r.integer("solver.threads", c.threads, 0, 256,
    "threads of one run; 0: automatic (the free cores; the deformable insert's loops)");
  r.integer("solver.cycles", c.cycles, 1, 1000000,
    "gait cycles of kneesim run; outputs come from the last");

  r.list("output.map_pcts", c.map_pcts, 0, 100,
    "gait percentages of the pressure maps (.vtp)");
  r.text("output.measured_kinematics", c.measured_kinematics,
    "measured kinematics drawn over the kinematics plot (CSV or .sto)");
  return r;
}

// Every rig parameter of a preset, with its source (docs/user-guide.md#rig-presets has the
// table, docs/validation.md#rig-parameters the measured sensitivity of the AP and IE ranges to
// each assumed one). The carriage masses and dampers are the same for every preset
// (config.h: this project's assumptions, docs/validation.md#carriage-masses).
void apply_rig_preset(Config& c) {
  using A = std::array<std::string, 6>;  // ap, is, ml, vv, ie, fe
  if (c.rig_preset == "stanmore" || c.rig_preset == "iso") {
    // a force-controlled Stanmore/Instron-type simulator (Pal 2008's rig): the femoral
    // carriage flexes (FE prescribed) and carries the axial load (IS force), its other DOFs
    // locked; the tibial carriage takes the AP force and IE torque against the restraint and
    // floats in ML and VV (physics.md section 1: this project's reading of such a rig; Pal's
    // text names the simulator and its springs, not every DOF)
    c.femur_dofs = A{"locked", "force", "locked", "locked", "locked", "prescribed"};
    c.tibia_dofs = A{"force", "locked", "free", "free", "force", "locked"};
    // assumption: the tibial VV/IE pivot 5 mm medial of the insert centre, for a medial share
    // of about 60 % in stance (61 % on the built-in implant; 50 % central, 73 % at 10 mm; IE
    // range -6 % / +16 %: docs/validation.md#rig-parameters). The axial load line's offset has
    // no effect while the femoral VV is locked (the lock takes its moment)
    c.axial_offset_mm = 5.0;
    c.tibia_pivot_medial_mm = 5.0;
  } else if (c.rig_preset == "materials_study") {
    // the materials study's boundary conditions (its text, physics.md section 6): femoral
    // component free in ML, AP and VV, constrained in IE, flexion displacement-controlled,
    // axial load on it offset medially for a 60:40 split; tibial insert free in ML and VV,
    // constrained in SI and FE, AP force and IE torque on it against four linear springs.
    // Two carriages free in the same DOF: the femur free in AP carries no AP force across the
    // joint, so the springs take the whole AP force (tibial travel F_AP / k, the restraint
    // force equal to the applied one) and the joint's AP follows the contact alone; in ML and
    // VV nothing restrains the pair's common motion. kneesim frees each joint DOF once, on the
    // femur: AP, ML and VV free there, the tibia locked in AP, ML and VV. The joint motion is
    // the literal rig's: the CVODE reference of the literal rig (femur AP free, tibia AP
    // force with the springs) gives the same joint AP and IE ranges within 1-2 % and a tibial
    // travel of -6.3..2.6 mm (docs/validation.md#rig-presets,
    // tests/cli_wear/rig_presets_test.cpp)
    c.femur_dofs = A{"free", "force", "free", "free", "locked", "prescribed"};
    c.tibia_dofs = A{"locked", "locked", "locked", "locked", "force", "locked"};
    // the study gives the split, not the offset (assumption): 5 mm gives 61 % medial on the
    // built-in implant (56 % at 3 mm, 65 % at 7 mm; IE range -1.0 % / +1.8 %)
    c.axial_offset_mm = 5.0;
    // assumption: the IE axis through the insert centre (5 mm medial: IE range +0.4 %)
    c.tibia_pivot_medial_mm = 0.0;
  } else {  // displacement: AP and IE prescribed (ISO 14243-3-shaped), otherwise as stanmore
    c.femur_dofs = A{"locked", "force", "locked", "locked", "locked", "prescribed"};
    c.tibia_dofs = A{"prescribed", "locked", "free", "free", "prescribed", "locked"};
    c.axial_offset_mm = 5.0;
    c.tibia_pivot_medial_mm = 5.0;
  }
  if (c.rig_preset == "stanmore") {
    // Pal 2008's Stanmore springs (its table of study variables, mean): anterior 4.75 N/mm,
    // posterior 22.18 N/mm, insert-to-springs distance 3.0 mm (the table's mean; its text
    // reads 2.5 mm: AP range -4.4 %, IE -1.4 %, docs/validation.md#rig-parameters; the table
    // is what Pal's probabilistic study sampled, and `kneesim study` centres on it). Four
    // springs, two per side of the IE axis; their lever arm is this project's assumption
    // (35 mm; Pal gives none: IE range +8.0 % at 25 mm, -9.5 % at 45 mm)
    c.restraint = "springs";
    c.gap_mm = 3.0;
    c.k_anterior_N_per_mm = 4.75;
    c.k_posterior_N_per_mm = 22.18;
    c.k_inside_N_per_mm = 0.0;
    c.spring_arm_mm = 35.0;
    c.ie_gap_deg = 0.0;
    c.k_ie_inside_Nm_per_deg = c.k_ie_Nm_per_deg = 0.0;
  } else if (c.rig_preset == "materials_study") {
    // the study's four linear springs of 10.4 N/mm each: 41.6 N/mm in AP (reading the
    // stiffness as the whole restraint's, 10.4 N/mm, would let the tibial carriage travel
    // -25..+11 mm under the AP force); 0.30 N m/deg in IE, no gap. The AP springs act only on
    // a free tibial AP (rig.tibia.ap = "force"): in the preset they take the whole AP force
    c.restraint = "linear";
    c.gap_mm = 0.0;
    c.k_anterior_N_per_mm = c.k_posterior_N_per_mm = 4.0 * 10.4;
    c.k_inside_N_per_mm = 0.0;
    c.ie_gap_deg = 0.0;
    c.k_ie_inside_Nm_per_deg = 0.0;
    c.k_ie_Nm_per_deg = 0.30;
  } else if (c.rig_preset == "iso") {
    // ISO 14243-1:2009-like soft-tissue restraint: physics.md's values, a recollection of the
    // standard that could not be checked against its text (approximate, unverified; its gaps
    // move the AP / IE range by up to 5 % / 7 %: docs/validation.md#rig-parameters)
    c.restraint = "linear";
    c.gap_mm = 2.5;
    c.k_inside_N_per_mm = 9.3;
    c.k_anterior_N_per_mm = c.k_posterior_N_per_mm = 44.0;
    c.ie_gap_deg = 6.0;
    c.k_ie_inside_Nm_per_deg = 0.13;
    c.k_ie_Nm_per_deg = 0.36;
  } else {
    c.restraint = "none";
  }
}

}  // namespace kneesim::models::config_detail
