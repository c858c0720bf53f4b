// Config loading: keys are registered once with their type and range; the file (read through
// the toml++ adapter, engine/io/toml_file.h) and the --set overrides are flattened to dotted keys
// and assigned through the registry, so every error names file, line, key, value and the allowed
// range.
#include "models/config.h"
#include "models/contact_law_file.h"

#include <cmath>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <variant>

#include "engine/errors.h"
#include "engine/io/toml_file.h"

namespace kneesim::models {
namespace {

using Value = io::TomlValue;
using io::describe;

struct Entry {
  Value value;
  std::string origin;  // "file:line" or "--set key=value"
};

std::map<std::string, Entry> with_origins(const io::TomlDocument& doc, const std::string& file) {
  std::map<std::string, Entry> out;
  for (const auto& [key, e] : doc) {
    out[key] = {e.value, e.line > 0 ? file + ":" + std::to_string(e.line) : file};
  }
  return out;
}

// one registered key: how to assign it and what is allowed
struct Field {
  std::function<void(const Value&, const std::string& where)> assign;
  std::string allowed;
  const double* number = nullptr;  // the target of a number key
  double lo = 0.0, hi = 0.0;       // its allowed range
};

[[noreturn]] void fail_value(const std::string& where, const std::string& key, const Value& v,
                             const std::string& allowed) {
  throw InputError(where + ": key '" + key + "' = " + describe(v) + " is not allowed (" +
                   allowed + ")");
}

class Registry {
 public:
  void number(const std::string& key, double& target, double lo, double hi) {
    std::ostringstream a;
    a << "a number in [" << lo << ", " << hi << "]";
    const std::string allowed = a.str();
    fields_[key] = {[&target, key, lo, hi, allowed](const Value& v, const std::string& where) {
                      const double* d = std::get_if<double>(&v);
                      if (!d || !std::isfinite(*d) || *d < lo || *d > hi)
                        fail_value(where, key, v, allowed);
                      target = *d;
                    },
                    allowed, &target, lo, hi};
  }
  void integer(const std::string& key, int& target, int lo, int hi) {
    const std::string allowed =
        "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    fields_[key] = {[&target, key, lo, hi, allowed](const Value& v, const std::string& where) {
                      const double* d = std::get_if<double>(&v);
                      if (!d || *d != std::floor(*d) || *d < lo || *d > hi)
                        fail_value(where, key, v, allowed);
                      target = static_cast<int>(*d);
                    },
                    allowed};
  }
  // a sign flip: exactly -1 or +1 (a fraction would silently scale the channel)
  void sign(const std::string& key, double& target) {
    fields_[key] = {[&target, key](const Value& v, const std::string& where) {
                      const double* d = std::get_if<double>(&v);
                      if (!d || (*d != 1.0 && *d != -1.0)) fail_value(where, key, v, "-1 or 1");
                      target = *d;
                    },
                    "-1 or 1"};
  }
  void text(const std::string& key, std::string& target) {
    fields_[key] = {[&target, key](const Value& v, const std::string& where) {
                      const std::string* s = std::get_if<std::string>(&v);
                      if (!s) fail_value(where, key, v, "a string");
                      target = *s;
                    },
                    "a string"};
  }
  void choice(const std::string& key, std::string& target, std::vector<std::string> options) {
    std::string allowed = "one of";
    for (const auto& o : options) allowed += " \"" + o + "\"";
    fields_[key] = {[&target, key, options, allowed](const Value& v, const std::string& where) {
                      const std::string* s = std::get_if<std::string>(&v);
                      if (!s || std::find(options.begin(), options.end(), *s) == options.end())
                        fail_value(where, key, v, allowed);
                      target = *s;
                    },
                    allowed};
  }
  void flag(const std::string& key, bool& target) {
    fields_[key] = {[&target, key](const Value& v, const std::string& where) {
                      const bool* b = std::get_if<bool>(&v);
                      if (!b) fail_value(where, key, v, "true or false");
                      target = *b;
                    },
                    "true or false"};
  }
  void vec3(const std::string& key, std::array<double, 3>& target) {
    fields_[key] = {[&target, key](const Value& v, const std::string& where) {
                      const auto* l = std::get_if<std::vector<double>>(&v);
                      if (!l || l->size() != 3) fail_value(where, key, v, "a list of 3 numbers");
                      for (int i = 0; i < 3; ++i) target[i] = (*l)[i];
                    },
                    "a list of 3 numbers"};
  }
  void list(const std::string& key, std::vector<double>& target, double lo, double hi) {
    std::ostringstream a;
    a << "a list of numbers in [" << lo << ", " << hi << "]";
    const std::string allowed = a.str();
    fields_[key] = {[&target, key, lo, hi, allowed](const Value& v, const std::string& where) {
                      const auto* l = std::get_if<std::vector<double>>(&v);
                      if (!l) fail_value(where, key, v, allowed);
                      for (double x : *l)
                        if (!std::isfinite(x) || x < lo || x > hi) fail_value(where, key, v, allowed);
                      target = *l;
                    },
                    allowed};
  }
  void strings(const std::string& key, std::vector<std::string>& target) {
    fields_[key] = {[&target, key](const Value& v, const std::string& where) {
                      const auto* l = io::as_string_list(v);
                      if (!l) fail_value(where, key, v, "a list of strings");
                      target = *l;
                    },
                    "a list of strings"};
  }
  const Field* find(const std::string& key) const {
    auto it = fields_.find(key);
    return it == fields_.end() ? nullptr : &it->second;
  }
  std::string keys_in_section(const std::string& key) const {
    const std::string section = key.substr(0, key.rfind('.') + 1);
    std::string out;
    for (const auto& [k, f] : fields_) {
      if (k.rfind(section, 0) == 0 && k.find('.', section.size()) == std::string::npos)
        out += (out.empty() ? "" : ", ") + k;
    }
    return out;
  }

 private:
  std::map<std::string, Field> fields_;
};

const std::vector<std::string> kDofModes = {"locked", "free", "prescribed", "force"};
const std::vector<std::string> kDofKeys = {"ap", "is", "ml", "vv", "ie", "fe"};

void register_material(Registry& r, const std::string& prefix, MaterialConfig& m) {
  r.number(prefix + "elastic_modulus_MPa", m.elastic_modulus_MPa, 1.0, 1e6);
  r.number(prefix + "poisson", m.poisson, 0.0, 0.49);
  r.number(prefix + "yield_MPa", m.yield_MPa, 0.0, 1e4);
  r.number(prefix + "density_g_per_cm3", m.density_g_per_cm3, 0.1, 30.0);
  r.number(prefix + "friction", m.friction, 0.0, 1.0);
  r.number(prefix + "wear_factor_mm3_per_Nmm", m.wear_factor_mm3_per_Nmm, 0.0, 1e-3);
  r.text(prefix + "source", m.source);
}

Registry make_registry(Config& c) {
  Registry r;
  r.choice("implant.kind", c.implant_kind, {"generic", "mesh"});
  r.number("implant.edge_length_mm", c.edge_length_mm, 0.2, 5.0);
  r.number("implant.generic.femur_distal_radius_mm", c.femur_distal_radius_mm, 15, 80);
  r.number("implant.generic.femur_posterior_radius_mm", c.femur_posterior_radius_mm, 10, 60);
  r.number("implant.generic.femur_coronal_radius_mm", c.femur_coronal_radius_mm, 5, 1000);
  r.number("implant.generic.condyle_width_mm", c.condyle_width_mm, 8, 40);
  r.number("implant.generic.condyle_spacing_mm", c.condyle_spacing_mm, 20, 70);
  r.number("implant.generic.insert_sagittal_radius_mm", c.insert_sagittal_radius_mm, 20, 1000);
  r.number("implant.generic.insert_coronal_radius_mm", c.insert_coronal_radius_mm, 5, 1000);
  r.number("implant.generic.insert_thickness_mm", c.insert_thickness_mm, 4, 30);
  r.number("implant.generic.insert_ap_depth_mm", c.insert_ap_depth_mm, 25, 80);
  r.number("implant.generic.insert_ml_width_mm", c.insert_ml_width_mm, 40, 100);
  r.text("implant.mesh.femur", c.femur_mesh);
  r.text("implant.mesh.insert", c.insert_mesh);
  r.choice("implant.mesh.units", c.mesh_units, {"m", "mm"});
  r.vec3("implant.mesh.rotation_deg", c.mesh_rotation_deg);
  r.flag("implant.mesh.left_knee", c.mesh_left_knee);
  r.vec3("implant.mesh.femur_origin_mm", c.femur_origin_mm);
  r.number("implant.mesh.insert_base_y_mm", c.insert_base_y_mm, -100, 100);
  r.number("implant.mesh.articular_min_normal_y", c.articular_min_normal_y, -1, 1);
  r.flag("implant.mesh.insert_closed", c.insert_closed);

  r.text("material.name", c.material.name);
  register_material(r, "material.", c.material);

  r.choice("contact.law", c.contact_law, {"linear", "nonlinear"});
  r.number("contact.damping_ratio", c.contact_damping_ratio, 0.0, 1.0);
  r.number("contact.sdf_spacing_mm", c.sdf_spacing_mm, 0.05, 2.0);
  r.number("contact.sdf_band_mm", c.sdf_band_mm, 0.5, 10.0);
  r.number("contact.friction_regularization_mm_per_s", c.friction_regularization_mm_per_s, 1e-4,
           100.0);
  r.number("contact.runaway_fraction", c.runaway_fraction, 0.01, 0.95);
  r.number("contact.friction", c.friction_override, 0.0, 1.0);
  r.text("contact.law_file", c.contact_law_file);
  r.number("contact.foundation_modulus_MPa", c.contact_foundation_modulus_MPa, 0.0, 1e6);

  r.choice("rig.preset", c.rig_preset, {"stanmore", "materials_study", "displacement", "iso"});
  for (int i = 0; i < 6; ++i) {
    r.choice("rig.femur." + kDofKeys[i], c.femur_dofs[i], kDofModes);
    r.choice("rig.tibia." + kDofKeys[i], c.tibia_dofs[i], kDofModes);
  }
  r.number("rig.axial_offset_mm", c.axial_offset_mm, -30, 30);
  r.number("rig.tibia_pivot_medial_mm", c.tibia_pivot_medial_mm, -30, 30);
  r.number("rig.femur_vv_deg", c.femur_vv_deg, -15, 15);
  r.number("rig.femur_mass_kg", c.femur_mass_kg, 0.01, 1000);
  r.number("rig.tibia_mass_kg", c.tibia_mass_kg, 0.01, 1000);
  r.number("rig.femur_inertia_kgm2", c.femur_inertia_kgm2, 1e-6, 100);
  r.number("rig.tibia_inertia_kgm2", c.tibia_inertia_kgm2, 1e-6, 100);
  r.number("rig.ap_damping_Ns_per_m", c.ap_damping_Ns_per_m, 0, 1e5);
  r.number("rig.ml_damping_Ns_per_m", c.ml_damping_Ns_per_m, 0, 1e5);
  r.number("rig.is_damping_Ns_per_m", c.is_damping_Ns_per_m, 0, 1e5);
  r.number("rig.ie_damping_Nms_per_rad", c.ie_damping_Nms_per_rad, 0, 1e3);
  r.number("rig.vv_damping_Nms_per_rad", c.vv_damping_Nms_per_rad, 0, 1e3);
  r.choice("rig.restraint.kind", c.restraint, {"springs", "linear", "none"});
  r.number("rig.restraint.gap_mm", c.gap_mm, 0, 20);
  r.number("rig.restraint.k_anterior_N_per_mm", c.k_anterior_N_per_mm, 0, 1e4);
  r.number("rig.restraint.k_posterior_N_per_mm", c.k_posterior_N_per_mm, 0, 1e4);
  r.number("rig.restraint.k_inside_N_per_mm", c.k_inside_N_per_mm, 0, 1e4);
  r.number("rig.restraint.spring_arm_mm", c.spring_arm_mm, 0, 200);
  r.number("rig.restraint.ie_gap_deg", c.ie_gap_deg, 0, 45);
  r.number("rig.restraint.k_ie_inside_Nm_per_deg", c.k_ie_inside_Nm_per_deg, 0, 100);
  r.number("rig.restraint.k_ie_Nm_per_deg", c.k_ie_Nm_per_deg, 0, 100);
  r.number("rig.alignment.femur_fe_axis_ap_mm", c.femur_fe_axis_ap_mm, -20, 20);
  r.number("rig.alignment.femur_fe_axis_is_mm", c.femur_fe_axis_is_mm, -20, 20);
  r.number("rig.alignment.tibia_ie_axis_ap_mm", c.tibia_ie_axis_ap_mm, -20, 20);
  r.number("rig.alignment.tibia_ie_axis_ml_mm", c.tibia_ie_axis_ml_mm, -20, 20);
  r.number("rig.alignment.femur_fe_deg", c.femur_fe_deg, -15, 15);
  r.number("rig.alignment.femur_ie_deg", c.femur_ie_deg, -15, 15);
  r.number("rig.alignment.insert_tilt_deg", c.insert_tilt_deg, -15, 15);

  r.text("gait.file", c.gait_file);
  r.text("gait.kinematics_file", c.kinematics_file);
  r.number("gait.period_s", c.period_s, 0.1, 100);
  r.sign("gait.ap_sign", c.ap_sign);
  r.sign("gait.ie_sign", c.ie_sign);
  r.number("gait.axial_force_scale", c.axial_force_scale, 0, 10);
  r.number("gait.ap_force_scale", c.ap_force_scale, 0, 10);
  r.number("gait.ie_torque_scale", c.ie_torque_scale, 0, 10);
  r.number("gait.vv_torque_axial_arm_mm", c.vv_torque_axial_arm_mm, -50, 50);
  r.number("gait.vv_torque_stance_arm_mm", c.vv_torque_stance_arm_mm, -50, 50);
  r.text("gait.measured.file", c.measured_file);
  r.text("gait.measured.time_column", c.measured_time_column);
  r.choice("gait.measured.time_unit", c.measured_time_unit, {"", "s", "ms", "pct"});
  r.list("gait.measured.window", c.measured_window, -1e6, 1e6);
  r.text("gait.measured.force_unit", c.measured_force_unit);
  r.text("gait.measured.moment_unit", c.measured_moment_unit);
  r.text("gait.measured.angle_unit", c.measured_angle_unit);
  r.text("gait.measured.length_unit", c.measured_length_unit);
  r.strings("gait.measured.channels", c.measured_channels);
  r.strings("gait.measured.compare", c.measured_compare);
  r.number("gait.ap_force_shift_pct", c.ap_force_shift_pct, -50, 50);
  r.number("gait.ie_torque_shift_pct", c.ie_torque_shift_pct, -50, 50);

  r.choice("insert", c.insert_kind, {"rigid", "deformable"});
  r.number("deformable.element_size_mm", c.deformable_element_size_mm, 0.2, 10.0);
  r.integer("deformable.layers", c.deformable_layers, 1, 20);
  r.number("deformable.grading", c.deformable_grading, 0.05, 20.0);
  r.number("deformable.dt_us", c.deformable_dt_us, 0.0, 1000.0);
  r.number("deformable.damping_per_s", c.deformable_damping_per_s, 0.0, 1e5);
  r.choice("deformable.material", c.deformable_material, {"elastoplastic", "elastic"});
  r.number("deformable.hardening_MPa", c.deformable_hardening_MPa, 0.0, 1e5);
  r.number("deformable.yield_cap_MPa", c.deformable_yield_cap_MPa, 0.0, 1e4);

  r.choice("solver.integrator", c.integrator, {"central_difference", "cvode"});
  r.number("solver.dt_safety", c.dt_safety, 0.05, 1.0);
  r.integer("solver.threads", c.threads, 1, 256);
  r.integer("solver.cycles", c.cycles, 1, 1000000);

  r.list("output.map_pcts", c.map_pcts, 0, 100);
  r.text("output.measured_kinematics", c.measured_kinematics);
  return r;
}

void apply_rig_preset(Config& c) {
  using A = std::array<std::string, 6>;  // ap, is, ml, vv, ie, fe
  if (c.rig_preset == "stanmore" || c.rig_preset == "iso") {
    c.femur_dofs = A{"locked", "force", "locked", "locked", "locked", "prescribed"};
    c.tibia_dofs = A{"force", "locked", "free", "free", "force", "locked"};
    c.axial_offset_mm = 5.0;
    c.tibia_pivot_medial_mm = 5.0;
  } else if (c.rig_preset == "materials_study") {
    // the materials study's rig (physics.md section 1): femoral FE prescribed, IS axial force,
    // AP free, IE locked; tibial AP force and IE torque with the linear restraint, IS and FE
    // locked. The study lists ML and VV free on both carriages; two rigid carriages free in the
    // same DOF leave their common motion unrestrained (only the carriage dampers hold it: the
    // pair drifts off in VV, "runaway motion" at t = 0.09 s), so each joint DOF is freed once,
    // on the femoral carriage, which carries the medially offset axial load: its VV freedom is
    // what shares the load 60:40 between the condyles (physics.md section 1)
    c.femur_dofs = A{"free", "force", "free", "free", "locked", "prescribed"};
    c.tibia_dofs = A{"force", "locked", "locked", "locked", "force", "locked"};
    c.axial_offset_mm = 5.0;
    c.tibia_pivot_medial_mm = 0.0;
  } else {  // displacement
    c.femur_dofs = A{"locked", "force", "locked", "locked", "locked", "prescribed"};
    c.tibia_dofs = A{"prescribed", "locked", "free", "free", "prescribed", "locked"};
    c.axial_offset_mm = 5.0;
    c.tibia_pivot_medial_mm = 5.0;
  }
  if (c.rig_preset == "stanmore") {  // Pal 2008
    c.restraint = "springs";
    c.gap_mm = 3.0;
    c.k_anterior_N_per_mm = 4.75;
    c.k_posterior_N_per_mm = 22.18;
    c.k_inside_N_per_mm = 0.0;
    c.ie_gap_deg = 0.0;
    c.k_ie_inside_Nm_per_deg = c.k_ie_Nm_per_deg = 0.0;
  } else if (c.rig_preset == "materials_study") {
    c.restraint = "linear";
    c.gap_mm = 0.0;
    c.k_anterior_N_per_mm = c.k_posterior_N_per_mm = 10.4;
    c.k_inside_N_per_mm = 0.0;
    c.ie_gap_deg = 0.0;
    c.k_ie_inside_Nm_per_deg = 0.0;
    c.k_ie_Nm_per_deg = 0.30;
  } else if (c.rig_preset == "iso") {  // ISO 14243-1:2009-like, approx.
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

std::string materials_library_path() {
  return std::string(KNEESIM_SOURCE_DIR) + "/models/materials.toml";
}

// materials are tables of their own: "<section>.<name>.<key>" entries, removed from `flat`
std::map<std::string, MaterialConfig> take_material_tables(std::map<std::string, Entry>& flat,
                                                           const std::string& section) {
  std::map<std::string, MaterialConfig> out;
  const std::string prefix = section.empty() ? "" : section + ".";
  for (auto it = flat.lower_bound(prefix); it != flat.end() && it->first.starts_with(prefix);) {
    const std::string rest = it->first.substr(prefix.size());
    const auto dot = rest.find('.');
    if (dot == std::string::npos) {
      throw InputError(it->second.origin + ": '" + it->first + "' must be a table of material "
                       "properties");
    }
    const std::string name = rest.substr(0, dot);
    const std::string key = rest.substr(dot + 1);
    auto [mat, fresh] = out.try_emplace(name);
    if (fresh) mat->second.name = name;
    Registry r;
    register_material(r, "", mat->second);
    const Field* f = r.find(key);
    if (!f) {
      throw InputError(it->second.origin + ": unknown key '" + it->first + "' (allowed: "
                       "elastic_modulus_MPa, poisson, yield_MPa, density_g_per_cm3, friction, "
                       "wear_factor_mm3_per_Nmm, source)");
    }
    f->assign(it->second.value, it->second.origin + " [" + it->first + "]");
    it = flat.erase(it);
  }
  return out;
}

const std::map<std::string, MaterialConfig>& library() {
  static const std::map<std::string, MaterialConfig> lib = [] {
    const std::string path = materials_library_path();
    auto flat = with_origins(io::read_toml_file(path), path);
    return take_material_tables(flat, "");
  }();
  return lib;
}

// [conditions.<name>] set = ["key=value", ...]; the entries are removed from `flat`
std::map<std::string, std::vector<std::string>> take_conditions(std::map<std::string, Entry>& flat) {
  std::map<std::string, std::vector<std::string>> out;
  const std::string prefix = "conditions.";
  for (auto it = flat.lower_bound(prefix); it != flat.end() && it->first.starts_with(prefix);) {
    const std::string rest = it->first.substr(prefix.size());
    const auto dot = rest.find('.');
    const std::vector<std::string>* set = io::as_string_list(it->second.value);
    if (dot == std::string::npos || rest.substr(dot + 1) != "set" || !set) {
      throw InputError(it->second.origin + ": [conditions.<name>] must hold exactly one key, "
                       "set = [\"key=value\", ...] (found '" + it->first + "')");
    }
    for (const auto& text : *set) {
      if (text.find('=') == std::string::npos) {
        throw InputError(it->second.origin + ": " + it->first + " entry \"" + text +
                         "\" is not of the form \"key=value\"");
      }
    }
    out[rest.substr(0, dot)] = *set;
    it = flat.erase(it);
  }
  return out;
}

}  // namespace

std::vector<std::string> library_material_names() {
  std::vector<std::string> names;
  for (const auto& [k, v] : library()) names.push_back(k);
  return names;
}

MaterialConfig find_material(const Config& config, const std::string& name) {
  if (auto it = config.user_materials.find(name); it != config.user_materials.end())
    return it->second;
  if (auto it = library().find(name); it != library().end()) return it->second;
  std::string known;
  for (const auto& n : library_material_names()) known += " " + n;
  for (const auto& [n, m] : config.user_materials) known += " " + n;
  throw InputError((config.file.empty() ? std::string("material") : config.file.string()) +
                   ": unknown material '" + name + "' (known:" + known + ")");
}

Override parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 >= text.size()) {
    throw InputError("--set '" + text + "' is not of the form key=value");
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

std::filesystem::path resolve_path(const Config& config, const std::string& path) {
  std::string p = path;
  auto expand = [&p](const std::string& var, const std::string& fallback) {
    const std::string token = "${" + var + "}";
    for (auto pos = p.find(token); pos != std::string::npos; pos = p.find(token)) {
      const char* env = std::getenv(var.c_str());
      p.replace(pos, token.size(), env ? env : fallback);
    }
  };
  expand("KNEESIM_DATA", std::string(KNEESIM_SOURCE_DIR) + "/../shared/data");
  expand("KNEESIM_SOURCE", KNEESIM_SOURCE_DIR);
  std::filesystem::path out(p);
  if (out.is_relative() && !config.file.empty()) out = config.file.parent_path() / out;
  return out;
}

std::optional<NumberKey> find_number_key(const Config& config, const std::string& key) {
  Config copy = config;
  const Registry registry = make_registry(copy);
  const Field* f = registry.find(key);
  if (!f || !f->number) return std::nullopt;
  return NumberKey{*f->number, f->lo, f->hi};
}

Config load_config(const std::filesystem::path& file, const std::vector<Override>& overrides) {
  Config c;
  c.file = file;
  std::map<std::string, Entry> flat;
  if (!file.empty()) {
    if (!std::filesystem::exists(file)) {
      throw InputError(file.string() + ": config file not found");
    }
    flat = with_origins(io::read_toml_file(file), file.string());
    // user materials and named conditions are tables of their own, taken before the flat keys
    c.user_materials = take_material_tables(flat, "materials");
    c.conditions = take_conditions(flat);
  }
  for (const Override& o : overrides) {
    flat[o.key] = {io::parse_toml_value(o.value), "--set " + o.key + "=" + o.value};
  }
  Registry registry = make_registry(c);
  // pass 1: the preset and the material name set the defaults the other keys refine
  if (auto it = flat.find("rig.preset"); it != flat.end()) {
    registry.find("rig.preset")->assign(it->second.value, it->second.origin);
  }
  apply_rig_preset(c);
  if (auto it = flat.find("material.name"); it != flat.end()) {
    registry.find("material.name")->assign(it->second.value, it->second.origin);
  }
  c.material = find_material(c, c.material.name);
  // pass 2: every key, in order
  for (const auto& [key, entry] : flat) {
    const Field* f = registry.find(key);
    if (!f) {
      const std::string section = registry.keys_in_section(key);
      throw InputError(entry.origin + ": unknown config key '" + key + "'" +
                       (section.empty() ? "" : " (keys in its section: " + section + ")"));
    }
    f->assign(entry.value, entry.origin);
  }
  if (c.gait_file.empty()) {
    c.gait_file = c.rig_preset == "displacement"
                      ? "${KNEESIM_SOURCE}/loads/iso14243/iso14243_3_approx.csv"
                      : "${KNEESIM_SOURCE}/loads/iso14243/iso14243_1_approx.csv";
  }
  if (!c.contact_law_file.empty()) {
    // the calibrated law replaces the law and modulus, for this material and implant only
    const CalibratedContactLaw law = read_contact_law_file(
        resolve_path(c, c.contact_law_file), c.material.name, implant_identity(c));
    c.contact_law = law.law;
    c.contact_foundation_modulus_MPa = law.foundation_modulus_MPa;
  }
  if (c.implant_kind == "mesh" && (c.femur_mesh.empty() || c.insert_mesh.empty())) {
    throw InputError((file.empty() ? std::string("config") : file.string()) +
                     ": implant.kind = \"mesh\" needs both implant.mesh.femur and "
                     "implant.mesh.insert");
  }
  return c;
}

}  // namespace kneesim::models
