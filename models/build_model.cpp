#include "models/build_model.h"
#include "models/contact_law_file.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>
#include <numbers>

#include "engine/contact_law.h"
#include "engine/errors.h"
#include "engine/fcl_adapter.h"
#include "engine/kinematics.h"
#include "engine/step.h"
#include "models/deformable_insert.h"
#include "models/distance_field_cache.h"
#include "models/gait_assembly.h"
#include "models/implant_check.h"
#include "models/mesh_io.h"
#include "models/smooth_refine.h"

namespace kneesim::models {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kMm = 1e-3;
// the far field only decides how long distant elements may sleep (engine/contact.h)
constexpr double kFarSpacing = 2.5e-3;  // [m]
constexpr double kFarBand = 5e-3;    // [m]

std::string config_name(const Config& c) {
  return c.file.empty() ? std::string("built-in config") : c.file.string();
}

Eigen::Matrix3d rotation_xyz_deg(const std::array<double, 3>& deg) {
  // extrinsic x, then y, then z
  return (Eigen::AngleAxisd(deg[2] * kDeg, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(deg[1] * kDeg, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(deg[0] * kDeg, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// a knee component's largest extent lies far inside this range; outside it the mesh is not a
// knee implant in the declared units (a metre mesh declared as mm is 1000x too small)
constexpr double kMinImplantExtent = 15e-3;   // [m]
constexpr double kMaxImplantExtent = 300e-3;  // [m]

void check_implant_size(const TriMesh& m, const std::filesystem::path& file,
                        const std::string& units, const char* key) {
  Eigen::Vector3d lo = m.vertices.front(), hi = m.vertices.front();
  for (const auto& v : m.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const double extent = (hi - lo).maxCoeff();
  if (extent >= kMinImplantExtent && extent <= kMaxImplantExtent) return;
  const double in_units = extent / (units == "mm" ? kMm : 1.0);
  const char* hint = extent < kMinImplantExtent
                         ? (units == "mm" ? " (is the file in metres? set implant.mesh.units = \"m\")" : "")
                         : (units == "m" ? " (is the file in mm? set implant.mesh.units = \"mm\")" : "");
  char size[64], buf[400];
  if (units == "mm") {
    std::snprintf(size, sizeof size, "%g mm", in_units);
  } else {
    std::snprintf(size, sizeof size, "%g %s (%g mm)", in_units, units.c_str(), extent / kMm);
  }
  std::snprintf(buf, sizeof buf,
                "%s: implant.mesh.%s spans %s at its largest extent, but a knee component "
                "spans %g-%g mm%s.",
                file.string().c_str(), key, size, kMinImplantExtent / kMm,
                kMaxImplantExtent / kMm, hint);
  throw InputError(buf);
}

// The femoral distance field is built on a dense node grid over the femur's box grown by the
// band (engine/sdf.cpp; only the result is stored in bricks): while it is built each node
// holds a float best distance, an int nearest triangle, a float distance and two flag bytes.
// A fine spacing over a large femur would ask for tens of GB and die in allocation or thread
// start-up, so the estimate is checked first.
constexpr double kSdfBytesPerNode = 14.0;
constexpr double kSdfMemoryLimitBytes = 8e9;

void check_sdf_memory(const Config& c, const TriMesh& femur) {
  const double spacing = c.sdf_spacing_mm * kMm, band = c.sdf_band_mm * kMm;
  Eigen::Vector3d lo = femur.vertices.front(), hi = femur.vertices.front();
  for (const auto& v : femur.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const Eigen::Vector3d extent =
      hi - lo + Eigen::Vector3d::Constant(2.0 * (band + 2.0 * spacing));
  double nodes = 1.0;
  for (int a = 0; a < 3; ++a) nodes *= std::ceil(extent[a] / spacing) + 1.0;
  const double bytes = nodes * kSdfBytesPerNode;
  if (bytes <= kSdfMemoryLimitBytes) return;
  const double finest_mm = c.sdf_spacing_mm * std::cbrt(bytes / kSdfMemoryLimitBytes) * 1.01;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "%s: contact.sdf_spacing_mm = %g needs a femoral distance field of %.3g "
                "nodes, about %.1f GB while it is built; allowed: at most %.0f GB, i.e. "
                "contact.sdf_spacing_mm >= %.2f for this femur.",
                config_name(c).c_str(), c.sdf_spacing_mm, nodes, bytes * 1e-9,
                kSdfMemoryLimitBytes * 1e-9, std::ceil(finest_mm * 100.0) / 100.0);
  throw InputError(buf);
}

// the femoral mesh refined on a smooth surface until its median edge is at most
// implant.mesh.femur_refine_mm (models/smooth_refine.h); refuses a refinement that would pass
// kMaxRefinedTriangles, naming the finest target this mesh allows
constexpr double kMaxRefinedTriangles = 4e6;

TriMesh refine_femur(const Config& c, const TriMesh& femur) {
  SmoothRefineOptions o;
  o.levels = find_refine_levels(femur, c.femur_refine_mm * kMm);
  const double triangles = static_cast<double>(femur.triangles.size()) * std::pow(4.0, o.levels);
  if (triangles > kMaxRefinedTriangles) {
    int allowed = o.levels;
    while (allowed > 0 && femur.triangles.size() * std::pow(4.0, allowed) > kMaxRefinedTriangles) {
      --allowed;
    }
    const double finest = c.femur_refine_mm * std::pow(2.0, o.levels - allowed);
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "%s: implant.mesh.femur_refine_mm = %g would refine %s's %zu triangles to "
                  "%.3g; allowed: at most %.0f, i.e. implant.mesh.femur_refine_mm >= %.2g "
                  "for this mesh (or 0: no refinement).",
                  config_name(c).c_str(), c.femur_refine_mm,
                  resolve_path(c, c.femur_mesh).string().c_str(), femur.triangles.size(),
                  triangles, kMaxRefinedTriangles, finest);
    throw InputError(buf);
  }
  return refine_smooth(femur, o);
}

Implant make_implant(const Config& c, double& base_y) {
  Implant imp;
  if (c.implant_kind == "generic") {
    const GenericTkrParams p = generic_params(c);
    check_generic_tkr(p);
    imp.femur = make_generic_femur(p, c.edge_length_mm * kMm);
    imp.insert = make_generic_insert(p, c.edge_length_mm * kMm);
    base_y = 0.0;
  } else {
    MeshImportOptions o;
    o.units = c.mesh_units;
    o.rotation = rotation_xyz_deg(c.mesh_rotation_deg);
    o.mirror_z = c.mesh_left_knee;
    o.translation_m = -Eigen::Vector3d(c.femur_origin_mm[0], c.femur_origin_mm[1],
                                       c.femur_origin_mm[2]) * kMm;
    imp.femur = load_mesh(resolve_path(c, c.femur_mesh), o);
    check_implant_size(imp.femur, resolve_path(c, c.femur_mesh), c.mesh_units, "femur");
    if (c.femur_refine_mm > 0.0) imp.femur = refine_femur(c, imp.femur);
    o.translation_m.setZero();
    o.require_closed = c.insert_closed;
    imp.insert = load_mesh(resolve_path(c, c.insert_mesh), o);
    check_implant_size(imp.insert, resolve_path(c, c.insert_mesh), c.mesh_units, "insert");
    base_y = c.insert_base_y_mm * kMm;
    // put the insert base plane at y = 0 of T
    for (auto& v : imp.insert.vertices) v.y() -= base_y;
    base_y = 0.0;
    // refuse what the rig cannot use (same mesh twice, inside out, upside down, femur not
    // over the insert, flexion axis outside the femur) before any simulation
    check_implant(c, imp);
    // a frame that passes the checks but reverses anterior and posterior, or a flexion axis
    // off the condylar arcs, runs with a warning (kneesim implant check explains it)
    warn_about_frame(c, imp);
  }
  imp.insert_volume = c.insert_closed || c.implant_kind == "generic"
                          ? enclosed_volume(imp.insert) : 0.0;
  return imp;
}

engine::DofMode parse_mode(const std::string& s) {
  if (s == "free") return engine::DofMode::kFree;
  if (s == "prescribed") return engine::DofMode::kPrescribed;
  if (s == "force") return engine::DofMode::kForce;
  return engine::DofMode::kLocked;
}

// channel and SI scale of a DOF's waveform by carriage, DOF and mode
void map_channel(const Config& c, const loads::Waveform& gait, int carriage, int dof,
                 engine::DofModel& m) {
  using engine::DofMode;
  struct Map {
    int carriage, dof;
    DofMode mode;
    const char* channel;
    double scale;
  };
  const Map maps[] = {
      {0, 5, DofMode::kPrescribed, "flexion_deg", kDeg},
      {0, 1, DofMode::kForce, "axial_force_N", -c.axial_force_scale},
      {1, 0, DofMode::kForce, "ap_force_N", c.ap_force_scale},
      {1, 4, DofMode::kForce, "ie_torque_Nm", c.ie_torque_scale},
      {1, 0, DofMode::kPrescribed, "ap_mm", kMm * c.ap_displacement_scale},
      {1, 4, DofMode::kPrescribed, "ie_deg", kDeg * c.ie_rotation_scale},
      {1, 2, DofMode::kPrescribed, "ml_mm", kMm},
      {1, 3, DofMode::kPrescribed, "vv_deg", kDeg},
      {1, 3, DofMode::kForce, "vv_torque_Nm", 1.0},
  };
  for (const Map& mp : maps) {
    if (mp.carriage != carriage || mp.dof != dof || mp.mode != m.mode) continue;
    m.channel = gait.channel(mp.channel);
    m.scale = mp.scale;
    if (m.channel < 0) {
      throw InputError(gait.source() + ": the rig drives " +
                       std::string(carriage == 0 ? "femoral " : "tibial ") +
                       engine::kDofNames[dof] + " from channel '" + mp.channel +
                       "', which the waveform does not have (channels: " + [&] {
                         std::string s;
                         for (const auto& n : gait.channel_names()) s += " " + n;
                         return s;
                       }() + ")");
    }
    return;
  }
  if (m.mode == DofMode::kPrescribed) {
    throw InputError(config_name(c) + ": rig." + (carriage == 0 ? "femur." : "tibia.") +
                     engine::kDofNames[dof] + " = \"prescribed\" has no waveform channel; "
                     "allowed: femur fe; tibia ap, ie, ml, vv");
  }
}

std::vector<engine::RestraintSpring> make_restraint(const Config& c) {
  std::vector<engine::RestraintSpring> out;
  if (c.restraint == "none") return out;
  if (c.restraint == "springs") {
    // two AP springs per side at +-arm: each carries half of the side's stiffness
    for (double z : {-c.spring_arm_mm * kMm, c.spring_arm_mm * kMm}) {
      engine::RestraintSpring s;
      s.kind = engine::RestraintKind::kTranslational;
      s.z_arm = z;
      s.gap = c.gap_mm * kMm;
      s.k_inside = 0.5 * c.k_inside_N_per_mm / kMm;
      s.k_positive = 0.5 * c.k_anterior_N_per_mm / kMm;
      s.k_negative = 0.5 * c.k_posterior_N_per_mm / kMm;
      out.push_back(s);
    }
  } else {  // linear AP spring-gap at the pivot
    engine::RestraintSpring s;
    s.kind = engine::RestraintKind::kTranslational;
    s.gap = c.gap_mm * kMm;
    s.k_inside = c.k_inside_N_per_mm / kMm;
    s.k_positive = c.k_anterior_N_per_mm / kMm;
    s.k_negative = c.k_posterior_N_per_mm / kMm;
    out.push_back(s);
  }
  if (c.k_ie_Nm_per_deg > 0.0 || c.k_ie_inside_Nm_per_deg > 0.0) {
    engine::RestraintSpring r;
    r.kind = engine::RestraintKind::kRotational;
    r.gap = c.ie_gap_deg * kDeg;
    r.k_inside = c.k_ie_inside_Nm_per_deg / kDeg;
    r.k_positive = r.k_negative = c.k_ie_Nm_per_deg / kDeg;
    out.push_back(r);
  }
  return out;
}

// the femoral component's pose on its carriage (rig.alignment): turned by FE, then IE (the
// carriage's own gimbal order; its VV is the locked VV DOF's value, rig.femur_vv_deg) about its
// origin, then offset so that the carriage's FE axis sits at (femur_fe_axis_ap_mm,
// femur_fe_axis_is_mm) of the component
Eigen::Isometry3d femur_on_carriage(const Config& c) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (c.femur_fe_deg == 0.0 && c.femur_ie_deg == 0.0 &&
      c.femur_fe_axis_ap_mm == 0.0 && c.femur_fe_axis_is_mm == 0.0) {
    return X;
  }
  X.linear() = (Eigen::AngleAxisd(c.femur_fe_deg * kDeg, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(c.femur_ie_deg * kDeg, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  X.translation() = -Eigen::Vector3d(c.femur_fe_axis_ap_mm, c.femur_fe_axis_is_mm, 0.0) * kMm;
  return X;
}

// every key that shapes the meshes, the articular elements or the femoral distance fields, in
// full precision: two configs with the same key build the same geometry
std::string make_geometry_key(const Config& c) {
  std::string key = c.implant_kind;
  char buf[64];
  auto add = [&](double v) {
    std::snprintf(buf, sizeof buf, " %.17g", v);
    key += buf;
  };
  for (double v : {c.edge_length_mm, c.femur_distal_radius_mm, c.femur_posterior_radius_mm,
                   c.femur_coronal_radius_mm, c.condyle_width_mm, c.condyle_spacing_mm,
                   c.insert_sagittal_radius_mm, c.insert_coronal_radius_mm,
                   c.insert_thickness_mm, c.insert_ap_depth_mm, c.insert_ml_width_mm,
                   c.insert_base_y_mm, c.articular_min_normal_y, c.sdf_spacing_mm,
                   c.sdf_band_mm, c.femur_refine_mm}) {
    add(v);
  }
  for (double v : c.mesh_rotation_deg) add(v);
  for (double v : c.femur_origin_mm) add(v);
  if (c.implant_kind == "mesh") {
    for (const std::string& part : {resolve_path(c, c.femur_mesh).string(),
                                    resolve_path(c, c.insert_mesh).string(), c.mesh_units}) {
      key.append(1, ' ').append(part);
    }
  }
  key.append(c.mesh_left_knee ? " left" : " right");
  key.append(c.insert_closed ? " closed" : " open");
  return key;
}

// a whole number of steps per gait cycle, so frames and cycles land on steps
void apply_time_step(const engine::StableStepReport& r, engine::Model& m) {
  m.contact.damping_beta = r.damping_beta;
  m.dt_critical = r.dt_critical;
  const long steps = static_cast<long>(std::ceil(m.period / r.dt));
  m.dt = m.period / steps;
}

}  // namespace

Implant load_implant(const Config& c) {
  double base_y = 0.0;
  return make_implant(c, base_y);
}

GenericTkrParams generic_params(const Config& c) {
  GenericTkrParams p;
  p.femur_distal_radius_m = c.femur_distal_radius_mm * kMm;
  p.femur_posterior_radius_m = c.femur_posterior_radius_mm * kMm;
  p.femur_coronal_radius_m = c.femur_coronal_radius_mm * kMm;
  p.condyle_width_m = c.condyle_width_mm * kMm;
  p.condyle_spacing_m = c.condyle_spacing_mm * kMm;
  p.insert_sagittal_radius_m = c.insert_sagittal_radius_mm * kMm;
  p.insert_coronal_radius_m = c.insert_coronal_radius_mm * kMm;
  p.insert_thickness_m = c.insert_thickness_mm * kMm;
  p.insert_ap_depth_m = c.insert_ap_depth_mm * kMm;
  p.insert_ml_width_m = c.insert_ml_width_mm * kMm;
  p.insert_eminence_height_m = std::max(p.insert_eminence_height_m, p.insert_thickness_m + 4e-3);
  return p;
}

engine::InsertSurface make_insert_surface(const TriMesh& insert, double base_y,
                                          double min_normal_y, std::vector<int>* to_insert,
                                          std::vector<int>* vertex_to_insert) {
  const auto normals = face_normals(insert);
  const auto areas = face_areas(insert);
  const SubMesh sub = submesh(insert, [&](int f) {
    const auto& t = insert.triangles[f];
    const double cy =
        (insert.vertices[t[0]].y() + insert.vertices[t[1]].y() + insert.vertices[t[2]].y()) / 3;
    return normals[f].y() > min_normal_y && cy > base_y + 1e-4 && areas[f] > 0.0;
  });
  engine::InsertSurface s;
  s.vertices_T = sub.mesh.vertices;
  s.triangles = sub.mesh.triangles;
  for (size_t i = 0; i < sub.mesh.triangles.size(); ++i) {
    const int f = sub.triangle_to_parent[i];
    const auto& t = insert.triangles[f];
    const Eigen::Vector3d c =
        (insert.vertices[t[0]] + insert.vertices[t[1]] + insert.vertices[t[2]]) / 3.0;
    s.centroid_T.push_back(c);
    s.normal_T.push_back(normals[f]);
    s.area.push_back(areas[f]);
    // layer thickness: the height above the base plane (the insert sits on a rigid tray)
    s.thickness.push_back(std::max(c.y() - base_y, 1e-4));
    s.medial.push_back(c.z() < 0.0 ? 1 : 0);
  }
  if (to_insert) *to_insert = sub.triangle_to_parent;
  if (vertex_to_insert) *vertex_to_insert = sub.vertex_to_parent;
  return s;
}

engine::InsertSurface make_worn_insert_surface(const BuiltModel& pristine, const TriMesh& worn) {
  const engine::InsertSurface& s0 = pristine.model.insert;
  const auto& to_insert = pristine.implant.articular_to_insert;
  engine::InsertSurface s = s0;
  for (size_t v = 0; v < s.vertices_T.size(); ++v) {
    s.vertices_T[v] = worn.vertices[pristine.implant.articular_vertex_to_insert[v]];
  }
  for (int e = 0; e < s.size(); ++e) {
    const auto& t = worn.triangles[to_insert[e]];
    const Eigen::Vector3d& a = worn.vertices[t[0]];
    const Eigen::Vector3d& b = worn.vertices[t[1]];
    const Eigen::Vector3d& c = worn.vertices[t[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double len = n.norm();
    s.centroid_T[e] = (a + b + c) / 3.0;
    s.normal_T[e] = len > 0.0 ? Eigen::Vector3d(n / len) : s0.normal_T[e];
    s.area[e] = 0.5 * len;
    s.thickness[e] = std::max(s.centroid_T[e].y(), 1e-4);
  }
  return s;
}

BuiltModel build_model(const Config& c, const BuiltModel* same_geometry) {
  if (c.contact_law_resolution.needs_calibration && c.insert_kind != "deformable") {
    // meshes the rig cannot use are refused as themselves first (the more basic error)
    load_implant(c);
    // the law as specified would inflate the pressures silently (models/contact_law_library.h)
    throw InputError(
        (c.file.empty() ? std::string("config") : c.file.string()) +
        ": no calibrated contact law for implant \"" + implant_identity(c) + "\" and material \"" +
        c.material.name + "\" (key " + c.contact_law_resolution.key +
        "): the kneesim commands calibrate it on first use; give contact.calibration = \"off\" "
        "(--no-calibrate) for the law as specified, or name one (contact.law_file)");
  }
  const auto start = std::chrono::steady_clock::now();
  BuiltModel out;
  engine::Model& m = out.model;
  out.material = c.material;
  const MaterialConfig& mat = c.material;

  out.geometry_key = make_geometry_key(c);
  if (same_geometry && same_geometry->geometry_key == out.geometry_key) {
    // the same implant and field keys give the same meshes, elements and fields: copy them
    out.implant = same_geometry->implant;
    m.insert = same_geometry->model.insert;
    m.femur_sdf = same_geometry->model.femur_sdf;
    m.femur_far_sdf = same_geometry->model.femur_far_sdf;
    m.femur_radius = same_geometry->model.femur_radius;
  } else {
    // implant geometry and the insert's articular elements
    double base_y = 0.0;
    out.implant = make_implant(c, base_y);
    m.insert = make_insert_surface(out.implant.insert, base_y, c.articular_min_normal_y,
                                   &out.implant.articular_to_insert,
                                   &out.implant.articular_vertex_to_insert);
    if (m.insert.size() == 0) {
      throw InputError(config_name(c) + ": the insert has no articular faces (implant.mesh."
                       "articular_min_normal_y = " + std::to_string(c.articular_min_normal_y) +
                       "; allowed: below the largest face normal y)");
    }

    // femoral distance fields, built once per femoral mesh and field parameters in a process;
    // the build's dense scratch grid is sized before it is allocated
    check_sdf_memory(c, out.implant.femur);
    const auto sdf_start = std::chrono::steady_clock::now();
    m.femur_sdf = find_or_make_distance_field(out.implant.femur.vertices,
                                              out.implant.femur.triangles,
                                              c.sdf_spacing_mm * kMm, c.sdf_band_mm * kMm);
    m.femur_far_sdf = find_or_make_distance_field(
        out.implant.femur.vertices, out.implant.femur.triangles, kFarSpacing, kFarBand);
    for (const auto& v : out.implant.femur.vertices) {
      m.femur_radius = std::max(m.femur_radius, v.norm());
    }
    out.sdf_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - sdf_start).count();
  }

  // gait and rig
  m.gait = make_gait(c);
  m.period = c.period_s;
  if (!c.measured_file.empty()) {
    // a measured cycle in seconds sets the period
    const loads::MeasuredLoads measured = loads::read_measured_loads(measured_load_spec(c));
    if (!measured.percent) m.period = measured.window_end - measured.window_start;
  }
  // the rigid insert's parallel loop runs only in steps with thousands of due elements (the
  // first): automatic gives it one thread; the deformable insert resolves its own count
  m.threads = c.threads > 0 ? c.threads : 1;
  m.integrator = c.integrator == "cvode" ? engine::IntegratorKind::kCvode
                                         : engine::IntegratorKind::kCentralDifference;
  m.coupled_rig_step = c.rig_coupling == "coupled";
  const auto femur_box = bounding_box(out.implant.femur);
  double insert_top = 0.0;
  for (const auto& v : m.insert.vertices_T) insert_top = std::max(insert_top, v.y());
  for (int carriage = 0; carriage < 2; ++carriage) {
    engine::CarriageModel& cm = m.carriages[carriage];
    const auto& modes = carriage == 0 ? c.femur_dofs : c.tibia_dofs;
    const double mass[6] = {c.ap_mass_kg,      c.is_mass_kg,      c.ml_mass_kg,
                            c.vv_inertia_kgm2, c.ie_inertia_kgm2, c.fe_inertia_kgm2};
    const double damping[6] = {c.ap_damping_Ns_per_m,    c.is_damping_Ns_per_m,
                               c.ml_damping_Ns_per_m,    c.vv_damping_Nms_per_rad,
                               c.ie_damping_Nms_per_rad, c.ie_damping_Nms_per_rad};
    for (int i = 0; i < engine::kNumDof; ++i) {
      engine::DofModel& d = cm.dofs[i];
      d.mode = parse_mode(modes[i]);
      if (carriage == 1 && i == 3 && m.gait.channel("vv_torque_Nm") >= 0 &&
          (c.vv_torque_axial_arm_mm != 0.0 || c.vv_torque_stance_arm_mm != 0.0)) {
        // the VV torque drives a free tibial VV (the rig's free DOF plus a torque)
        if (d.mode == engine::DofMode::kFree) d.mode = engine::DofMode::kForce;
        if (d.mode != engine::DofMode::kForce) {
          throw InputError(config_name(c) + ": gait.vv_torque_axial_arm_mm / "
                           "vv_torque_stance_arm_mm need a free tibial VV (rig.tibia.vv = \"" +
                           modes[i] + "\"; allowed: \"free\" or \"force\")");
        }
      }
      if (carriage == 0 && i == 3 && c.femur_vv_deg != 0.0) {
        if (d.mode != engine::DofMode::kLocked) {
          throw InputError(config_name(c) + ": rig.femur_vv_deg = " +
                           std::to_string(c.femur_vv_deg) + " needs a locked femoral VV "
                           "(rig.femur.vv = \"" + modes[i] + "\"; allowed: \"locked\")");
        }
        d.initial = c.femur_vv_deg * kDeg;
      }
      if (carriage == 1 && i == 3 && c.femur_vv_deg != 0.0 &&
          (d.mode == engine::DofMode::kFree || d.mode == engine::DofMode::kForce)) {
        // a free tibial VV starts aligned with the femur (both condyles in contact at t = 0)
        d.initial = c.femur_vv_deg * kDeg;
      }
      d.mass = mass[i];
      d.damping = damping[i];
      // AP and IE are light, quasi-static DOFs (engine/model.h): their contact stiffness spans
      // two orders of magnitude between stance and swing, so no explicit mass is both small
      // enough for the swing phase and large enough for the stance step
      d.implicit = i == static_cast<int>(engine::Dof::kAp) || i == static_cast<int>(engine::Dof::kIe);
      map_channel(c, m.gait, carriage, i, d);
    }
  }
  // each joint DOF moves on one carriage only: a pair moved on both has nothing but the
  // restraint and the carriage masses to hold its common motion, and the explicit step's
  // per-DOF implicit friction locks the two together (engine/implicit_friction.h)
  if (m.integrator == engine::IntegratorKind::kCentralDifference) {
    for (int i = 0; i < engine::kNumDof; ++i) {
      auto moved = [&](int carriage) {
        const engine::DofMode mode = m.carriages[carriage].dofs[i].mode;
        return mode == engine::DofMode::kFree || mode == engine::DofMode::kForce;
      };
      if (!moved(0) || !moved(1)) continue;
      throw InputError(config_name(c) + ": rig.femur." + engine::kDofNames[i] + " = \"" +
                       c.femur_dofs[i] + "\" and rig.tibia." + engine::kDofNames[i] + " = \"" +
                       c.tibia_dofs[i] + "\" move the same joint DOF on both carriages; "
                       "allowed: one of them \"locked\" or \"prescribed\" (or "
                       "solver.integrator = \"cvode\", which integrates such a rig)");
    }
  }
  // femur: pivot on the FE axis, the component turned and offset from it (rig.alignment), first
  // placed just above the insert
  m.carriages[0].X_BP = femur_on_carriage(c);
  double femur_min_y = femur_box.min().y();
  if (!m.carriages[0].X_BP.matrix().isIdentity(0.0)) {
    femur_min_y = std::numeric_limits<double>::infinity();
    for (const auto& v : out.implant.femur.vertices)
      femur_min_y = std::min(femur_min_y, (m.carriages[0].X_BP * v).y());
  }
  m.carriages[0].pivot0_W = Eigen::Vector3d(0, insert_top - femur_min_y + 1e-3, 0);
  m.carriages[0].load_point_B = Eigen::Vector3d(0, 0, -c.axial_offset_mm * kMm);
  // tibia: pivot (the IE and VV axes) offset medially and by rig.alignment; the insert frame T
  // stays at the world origin, tilted about its own origin
  const Eigen::Vector3d tibial_axis_W(c.tibia_ie_axis_ap_mm * kMm, 0,
                                      (-c.tibia_pivot_medial_mm + c.tibia_ie_axis_ml_mm) * kMm);
  m.carriages[1].pivot0_W = tibial_axis_W;
  if (c.insert_tilt_deg != 0.0) {
    m.carriages[1].X_BP.linear() =
        Eigen::AngleAxisd(c.insert_tilt_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  m.carriages[1].X_BP.translation() = -tibial_axis_W;
  m.restraint = make_restraint(c);
  // contact
  const double friction = c.friction_override >= 0.0 ? c.friction_override : mat.friction;
  m.contact.law = c.contact_law == "linear" ? engine::ContactLaw::kLinear
                                            : engine::ContactLaw::kNonlinear;
  m.contact.exponent = c.contact_law_exponent;
  m.contact.foundation_modulus =
      c.contact_foundation_modulus_MPa > 0.0
          ? c.contact_foundation_modulus_MPa * 1e6  // calibrated (contact.law_file)
          : engine::foundation_modulus(mat.elastic_modulus_MPa * 1e6, mat.poisson);
  m.contact.friction = friction;
  m.contact.slip_regularization = c.friction_regularization_mm_per_s * kMm;
  m.contact.runaway_fraction = c.runaway_fraction;

  // stable step from the measured contact stiffness over the gait's flexion range
  const int fe_ch = m.carriages[0].dofs[5].channel;
  const int ax_ch = m.carriages[0].dofs[1].channel;
  double fe_min = 0.0, fe_max = 0.0, peak_load = 0.0;
  for (int i = 0; i <= 200; ++i) {
    const double pct = 0.5 * i;
    if (fe_ch >= 0) {
      const double fe = m.gait.value(fe_ch, pct) * kDeg;
      fe_min = std::min(fe_min, fe);
      fe_max = std::max(fe_max, fe);
    }
    if (ax_ch >= 0) peak_load = std::max(peak_load, -m.carriages[0].dofs[1].scale *
                                                        m.gait.value(ax_ch, pct));
  }
  std::vector<double> probes;
  for (int i = 0; i < 5; ++i) probes.push_back(fe_min + (fe_max - fe_min) * i / 4.0);
  out.peak_load = std::max(peak_load, 100.0);
  out.damping_ratio = c.contact_damping_ratio;
  out.dt_safety = c.dt_safety;
  out.stable_step = engine::calc_stable_time_step(m, out.peak_load, probes, out.damping_ratio,
                                                  out.dt_safety);
  apply_time_step(out.stable_step, m);

  // the femur starts at rest on the insert under the t = 0 axial load
  {
    engine::State s = engine::make_initial_state(m);
    engine::Data d = engine::make_data(m);
    const double load0 =
        ax_ch >= 0 ? -m.carriages[0].dofs[1].scale * m.gait.value(ax_ch, 0.0) : 0.0;
    engine::position_femur_statically(m, s, d, std::max(load0, 1.0));
    // a deformable insert starts undeformed: the femur at first touch, the rigid overlap lifted
    const double lift = c.insert_kind == "deformable" ? d.contact.max_penetration : 0.0;
    m.carriages[0].dofs[1].initial =
        s.carriages[0].pivot_W.y() + lift - m.carriages[0].pivot0_W.y();
  }
  // the deformable insert (hex8 solid) replaces the elastic foundation in the step
  if (c.insert_kind == "deformable") attach_deformable_insert(c, out);
  out.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace kneesim::models
