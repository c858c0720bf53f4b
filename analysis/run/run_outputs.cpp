#include "analysis/run/run_outputs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>

#include "analysis/report/file_hash.h"
#include "analysis/run/calibrate_contact_law.h"
#include "engine/io/vtp.h"

namespace kneesim::run {
namespace {
constexpr double kRadToDeg = 180.0 / std::numbers::pi;
}

io::Table make_kinematics_table(const std::vector<engine::Frame>& frames) {
  io::Table t;
  t.columns = {"gait_pct",          "time_s",           "flexion_deg",
               "ap_mm",             "ie_deg",           "ml_mm",
               "vv_deg",            "femur_is_mm",      "axial_force_N",
               "ap_force_N",        "ie_torque_Nm",     "contact_force_N",
               "contact_axial_force_N", "medial_force_N", "lateral_force_N",
               "contact_area_mm2",  "medial_area_mm2",  "lateral_area_mm2",
               "peak_pressure_MPa", "mean_pressure_MPa", "medial_cop_ap_mm",
               "medial_cop_ml_mm",  "lateral_cop_ap_mm", "lateral_cop_ml_mm",
               "restraint_force_N", "restraint_torque_Nm", "max_penetration_mm",
               "contact_line_area_mm2", "medial_line_area_mm2", "lateral_line_area_mm2",
               "mean_pressure_line_MPa"};
  for (const engine::Frame& f : frames) {
    const auto& c = f.contact;
    const double line_area = f.contact_line_area[0] + f.contact_line_area[1];
    const double normal_force = c.normal_force[0] + c.normal_force[1];
    t.add_row({f.gait_pct,
               f.time,
               f.joint.flexion * kRadToDeg,
               f.joint.ap * 1e3,
               f.joint.ie * kRadToDeg,
               f.joint.ml * 1e3,
               f.joint.vv * kRadToDeg,
               f.q[0][1] * 1e3,
               -f.applied[0][1],
               f.applied[1][0],
               f.applied[1][4],
               c.force_W.norm(),
               c.force_W.y(),
               c.normal_force[0],
               c.normal_force[1],
               (c.area[0] + c.area[1]) * 1e6,
               c.area[0] * 1e6,
               c.area[1] * 1e6,
               c.peak_pressure * 1e-6,
               c.mean_pressure * 1e-6,
               c.cop_T[0].x() * 1e3,
               c.cop_T[0].z() * 1e3,
               c.cop_T[1].x() * 1e3,
               c.cop_T[1].z() * 1e3,
               f.restraint.x(),
               f.restraint.y(),
               c.max_penetration * 1e3,
               line_area * 1e6,
               f.contact_line_area[0] * 1e6,
               f.contact_line_area[1] * 1e6,
               line_area > 0.0 ? normal_force / line_area * 1e-6 : 0.0});
  }
  return t;
}

CycleFigures calc_cycle_figures(const std::vector<engine::Frame>& frames) {
  CycleFigures fig;
  if (frames.empty()) return fig;
  double ap_lo = 1e9, ap_hi = -1e9, ie_lo = 1e9, ie_hi = -1e9;
  double peak_sum = 0.0, area_sum = 0.0, line_area_sum = 0.0, med = 0.0, lat = 0.0;
  int in_contact = 0;
  for (const engine::Frame& f : frames) {
    const double ap = f.joint.ap * 1e3, ie = f.joint.ie * kRadToDeg;
    ap_lo = std::min(ap_lo, ap);
    ap_hi = std::max(ap_hi, ap);
    ie_lo = std::min(ie_lo, ie);
    ie_hi = std::max(ie_hi, ie);
    const double p = f.contact.peak_pressure * 1e-6;
    fig.peak_pressure_MPa = std::max(fig.peak_pressure_MPa, p);
    fig.peak_contact_force_N = std::max(fig.peak_contact_force_N, f.contact.force_W.norm());
    if (f.contact.elements_in_contact > 0) {
      peak_sum += p;
      area_sum += (f.contact.area[0] + f.contact.area[1]) * 1e6;
      line_area_sum += (f.contact_line_area[0] + f.contact_line_area[1]) * 1e6;
      ++in_contact;
    }
    const double load = -f.applied[0][1];
    if (load > fig.peak_axial_load_N) {
      fig.peak_axial_load_N = load;
      fig.contact_force_at_peak_load_N = f.contact.force_W.y();
    }
    if (f.gait_pct <= 60.0) {
      med += f.contact.normal_force[0];
      lat += f.contact.normal_force[1];
    }
  }
  fig.ap_rom_mm = ap_hi - ap_lo;
  fig.ie_rom_deg = ie_hi - ie_lo;
  fig.mean_peak_pressure_MPa = in_contact ? peak_sum / in_contact : 0.0;
  fig.mean_contact_area_mm2 = in_contact ? area_sum / in_contact : 0.0;
  fig.mean_contact_line_area_mm2 = in_contact ? line_area_sum / in_contact : 0.0;
  fig.medial_fraction_stance = med + lat > 0 ? med / (med + lat) : 0.0;
  return fig;
}

nlohmann::json describe_model(const models::BuiltModel& built, const models::Config& config) {
  const engine::Model& m = built.model;
  nlohmann::json j;
  j["implant"] = config.implant_kind;
  j["femur_triangles"] = built.implant.femur.triangles.size();
  if (config.femur_refine_mm > 0.0) j["femur_refine_mm"] = config.femur_refine_mm;
  j["rig_preset"] = config.rig_preset;
  j["material"] = built.material.name;
  j["contact_law"] = config.contact_law;
  j["contact_foundation_modulus_MPa"] = m.contact.foundation_modulus * 1e-6;
  if (!config.contact_law_file.empty()) j["contact_law_file"] = config.contact_law_file;
  // which law, where it came from and how it was made (models/contact_law_library.h)
  j["contact_law_calibration"] = describe_contact_law(config, m.contact.foundation_modulus * 1e-6);
  if (!config.contact_law_resolution.warning.empty()) {
    j["contact_law_warning"] = config.contact_law_resolution.warning;
  }
  j["friction"] = m.contact.friction;
  j["integrator"] = config.integrator;
  j["rig_coupling"] = config.rig_coupling;
  j["gait_file"] = m.gait.source();
  j["gait_period_s"] = m.period;
  j["articular_elements"] = m.insert.size();
  j["dt_s"] = m.dt;
  j["dt_critical_s"] = m.dt_critical;
  j["steps_per_cycle"] = std::lround(m.period / m.dt);
  j["contact_damping_ratio"] = config.contact_damping_ratio;
  j["stable_step_governing_dof"] =
      std::string(built.stable_step.governing_carriage == 0 ? "femur_" : "tibia_") +
      engine::kDofNames[built.stable_step.governing_dof];
  for (int i = 0; i < engine::kNumDof; ++i) {
    // the generalized mass of each DOF the integrator moves, and whether it is a light one
    for (int c = 0; c < 2; ++c) {
      const engine::DofModel& d = m.carriages[c].dofs[i];
      if (d.mode != engine::DofMode::kFree && d.mode != engine::DofMode::kForce) continue;
      const std::string key = std::string(c == 0 ? "femur_" : "tibia_") + engine::kDofNames[i];
      j["rig_masses"][key] = d.mass;
      if (d.implicit) j["rig_light_dofs"].push_back(key);
    }
  }
  if (config.implant_kind == "mesh") {
    // which meshes, in which frame: enough to tell two runs' implants apart
    nlohmann::json meshes;
    for (const auto& [role, file] : {std::pair<std::string, std::string>{"femur", config.femur_mesh},
                                     {"insert", config.insert_mesh}}) {
      const std::filesystem::path p = models::resolve_path(config, file);
      meshes[role] = {{"file", p.string()}, {"sha256", report::sha256_file(p)}};
    }
    meshes["units"] = config.mesh_units;
    meshes["rotation_deg"] = config.mesh_rotation_deg;
    meshes["femur_origin_mm"] = config.femur_origin_mm;
    meshes["insert_base_y_mm"] = config.insert_base_y_mm;
    meshes["left_knee"] = config.mesh_left_knee;
    j["implant_meshes"] = meshes;
  }
  // the surfaces' resolution: the built-in implant's triangulation and the femur's distance
  // field (a calibration's --deformable-from run must match them)
  if (config.implant_kind == "generic") j["implant_edge_length_mm"] = config.edge_length_mm;
  j["sdf_spacing_mm"] = config.sdf_spacing_mm;
  j["build_seconds"] = built.build_seconds;
  j["sdf_seconds"] = built.sdf_seconds;
  if (!m.insert_solid.empty()) {
    // the [deformable] keys as given, and the mesh they made
    j["deformable_element_size_mm"] = config.deformable_element_size_mm;
    j["deformable_elements_across_contact"] = config.deformable_elements_across_contact;
    j["deformable_layers"] = config.deformable_layers;
    j["deformable_grading"] = config.deformable_grading;
    j["deformable_refine"] = config.deformable_refine;
    const models::DeformableMeshReport& d = built.deformable_mesh;
    j["deformable_mesh"] = {{"element_size_ap_mm", d.element_size_x * 1e3},
                            {"element_size_ml_mm", d.element_size_z * 1e3},
                            {"layers", d.layers},
                            {"grading", d.grading},
                            {"elements", d.elements},
                            {"rigid_patch_width_ap_mm", d.patch_width_x * 1e3},
                            {"rigid_patch_width_ml_mm", d.patch_width_z * 1e3},
                            {"contact_layer_thickness_mm", d.layer_thickness * 1e3}};
    if (!built.refined_x.empty()) {
      j["deformable_outer_element_size_mm"] = config.deformable_outer_element_size_mm;
      auto zone = [](const std::vector<models::Interval>& v) {
        nlohmann::json a = nlohmann::json::array();
        for (const auto& i : v) a.push_back({i.lo * 1e3, i.hi * 1e3});
        return a;
      };
      j["deformable_refined_zone_mm"] = {{"x", zone(built.refined_x)},
                                         {"z", zone(built.refined_z)}};
    }
  }
  return j;
}

nlohmann::json describe_figures(const CycleFigures& f) {
  nlohmann::json j;
  j["ap_rom_mm"] = f.ap_rom_mm;
  j["ie_rom_deg"] = f.ie_rom_deg;
  // deprecated alias of ie_rom_deg under the first release's misnamed key (degrees, not mm);
  // written in this release only, for scripts that read it (docs/user-guide.md)
  j["ie_rom_mm"] = f.ie_rom_deg;
  j["peak_pressure_MPa"] = f.peak_pressure_MPa;
  j["mean_peak_pressure_MPa"] = f.mean_peak_pressure_MPa;
  j["peak_contact_force_N"] = f.peak_contact_force_N;
  j["peak_axial_load_N"] = f.peak_axial_load_N;
  j["contact_axial_force_at_peak_load_N"] = f.contact_force_at_peak_load_N;
  j["medial_fraction_stance"] = f.medial_fraction_stance;
  j["mean_contact_area_mm2"] = f.mean_contact_area_mm2;
  j["mean_contact_line_area_mm2"] = f.mean_contact_line_area_mm2;
  return j;
}

void write_pressure_map(const std::filesystem::path& path, const engine::InsertSurface& insert,
                        const std::vector<double>& pressure_Pa) {
  io::VtpSurface s;
  for (const auto& v : insert.vertices_T) s.points_mm.push_back(v * 1e3);
  s.triangles = insert.triangles;
  io::VtpArray p{"pressure_MPa", {}};
  for (double x : pressure_Pa) p.values.push_back(x * 1e-6);
  s.cell_data.push_back(std::move(p));
  io::VtpArray h{"layer_thickness_mm", {}};
  for (double x : insert.thickness) h.values.push_back(x * 1e3);
  s.cell_data.push_back(std::move(h));
  io::write_vtp(path, s);
}

WearPotentialUnit wear_potential_unit(const std::string& law) {
  if (law == "contact_area") return {"mm3", 1e9, "mm³"};
  return {"Nmm", 1e3, "N mm"};
}

nlohmann::json describe_wear_law(const models::Config& c) {
  nlohmann::json j;
  j["wear_law"] = c.wear.law;
  nlohmann::json params = nlohmann::json::object();
  const auto value = [&c](const std::string& key) {
    const std::optional<models::NumberKey> n = models::find_number_key(c, "wear." + key);
    return n ? n->value : 0.0;
  };
  for (const std::string& key : models::wear_law_parameter_keys(c.wear.law)) {
    params[key] = value(key);
  }
  j["wear_law_params"] = params;
  j["creep"] = c.wear.creep;
  if (c.wear.creep) {
    j["creep_ratio"] = c.wear.creep_ratio;
    j["creep_time_s"] = c.wear.creep_time_s;
  }
  j["area_wear_coefficient"] = c.material.area_wear_coefficient;
  if (c.wear.law == "material_pressure") {  // the law's parameters are the material's
    j["wear_pressure_exponent"] = c.material.wear_pressure_exponent;
    j["wear_reference_pressure_MPa"] = c.material.wear_reference_pressure_MPa;
    j["wear_pressure_source"] = c.material.wear_pressure_source;
  }
  return j;
}

void write_wear_rate_map(const std::filesystem::path& path, const engine::InsertSurface& insert,
                         const wear::WearAccumulator& acc) {
  io::VtpSurface s;
  for (const auto& v : insert.vertices_T) s.points_mm.push_back(v * 1e3);
  s.triangles = insert.triangles;
  io::VtpArray rate{"wear_rate_mm_per_Mc", {}};
  for (double d : acc.depth_per_cycle()) rate.values.push_back(d * 1e3 * 1e6);
  s.cell_data.push_back(std::move(rate));
  io::VtpArray cs{"cross_shear_ratio", {}};
  for (double c : acc.cross_shear_ratio()) cs.values.push_back(c);
  s.cell_data.push_back(std::move(cs));
  io::write_vtp(path, s);
}

nlohmann::json describe_wear_rate(const engine::Model& model, const wear::WearAccumulator& acc,
                                  const models::Config& config) {
  nlohmann::json j = describe_wear_law(config);
  const std::vector<double> depth = acc.depth_per_cycle();
  // site areas: the rigid insert's elements or the deformable insert's top nodes
  const std::vector<double>& area =
      model.insert_solid.empty() ? model.insert.area : model.insert_contact.area;
  double volume = 0.0, peak = 0.0;
  for (size_t e = 0; e < depth.size(); ++e) {
    volume += depth[e] * area[e];
    peak = std::max(peak, depth[e]);
  }
  j["cycle_wear_rate_mm3_per_Mc"] = volume * 1e9 * 1e6;
  j["cycle_peak_wear_rate_mm_per_Mc"] = peak * 1e3 * 1e6;
  // the sliding-work-weighted cross-shear ratio, as wear.csv's cross_shear_ratio
  j["cycle_cross_shear_ratio"] = acc.mean_cross_shear();
  // what the law multiplies its coefficient by (volume = coefficient x potential)
  const WearPotentialUnit unit = wear_potential_unit(config.wear.law);
  j["cycle_wear_potential_" + unit.suffix] = acc.wear_potential() * unit.per_si;
  return j;
}

}  // namespace kneesim::run
