#include "models/contact_law_key.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>

#include "engine/errors.h"
#include "models/config.h"
#include "models/config_registry.h"

namespace kneesim::models {
namespace {

class Hash {
 public:
  void bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) {
      h_ ^= p[i];
      h_ *= 1099511628211ull;
    }
  }
  // text and numbers as text with a separator, so "1" "23" and "12" "3" differ
  void text(const std::string& s) {
    bytes(s.data(), s.size());
    bytes("\x1f", 1);
  }
  void number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    text(buf);
  }
  std::string hex() const {
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
    return buf;
  }

 private:
  uint64_t h_ = 1469598103934665603ull;
};

// the FNV-1a hash of a file's bytes, remembered per path, size and modification time (a
// study's trials load the same config hundreds of times)
std::string hash_file(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  const auto mtime = ec ? fs::file_time_type{} : fs::last_write_time(path, ec);
  if (ec) throw InputError(path.string() + ": mesh file not found.");
  static std::mutex mutex;
  static std::map<std::string, std::tuple<uintmax_t, fs::file_time_type, std::string>> memo;
  {
    std::lock_guard<std::mutex> lock(mutex);
    const auto it = memo.find(path.string());
    if (it != memo.end() && std::get<0>(it->second) == size && std::get<1>(it->second) == mtime) {
      return std::get<2>(it->second);
    }
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": mesh file cannot be read.");
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Hash h;
  h.bytes(content.data(), content.size());
  std::lock_guard<std::mutex> lock(mutex);
  memo[path.string()] = {size, mtime, h.hex()};
  return h.hex();
}

}  // namespace

ContactLawKey make_contact_law_key(const Config& c) {
  ContactLawKey k;
  Hash implant;
  implant.text(c.implant_kind);
  if (c.implant_kind == "generic") {
    for (double v : {c.femur_distal_radius_mm, c.femur_posterior_radius_mm,
                     c.femur_coronal_radius_mm, c.condyle_width_mm, c.condyle_spacing_mm,
                     c.insert_sagittal_radius_mm, c.insert_coronal_radius_mm,
                     c.insert_thickness_mm, c.insert_ap_depth_mm, c.insert_ml_width_mm}) {
      implant.number(v);
    }
  } else {
    implant.text(hash_file(resolve_path(c, c.femur_mesh)));
    implant.text(hash_file(resolve_path(c, c.insert_mesh)));
    implant.text(c.mesh_units);
    for (double v : c.mesh_rotation_deg) implant.number(v);
    for (double v : c.femur_origin_mm) implant.number(v);
    implant.text(c.mesh_left_knee ? "left" : "right");
    implant.number(c.insert_base_y_mm);
    implant.number(c.articular_min_normal_y);
    implant.text(c.insert_closed ? "closed" : "open");
  }
  k.implant = implant.hex();

  Hash material;
  const MaterialConfig& m = c.material;
  for (double v : {m.elastic_modulus_MPa, m.poisson, m.yield_MPa, m.density_g_per_cm3, m.friction}) {
    material.number(v);
  }
  k.material = material.hex();

  Hash settings;
  settings.text(c.contact_law);
  for (double v : {c.deformable_element_size_mm, static_cast<double>(c.deformable_layers),
                   static_cast<double>(c.deformable_elements_across_contact),
                   c.deformable_min_element_size_mm,
                   c.deformable_grading, c.deformable_outer_element_size_mm,
                   c.deformable_refine_margin_mm, c.deformable_dt_us, c.deformable_damping_per_s,
                   c.deformable_hardening_MPa, c.deformable_yield_cap_MPa}) {
    settings.number(v);
  }
  settings.text(c.deformable_refine);
  settings.text(c.deformable_material);
  k.settings = settings.hex();

  Hash all;
  all.number(kContactCalibrationVersion);
  for (const std::string* s : {&k.implant, &k.material, &k.settings}) all.text(*s);
  k.key = all.hex();
  return k;
}

Config make_calibration_config(const Config& c, bool own_reference) {
  // the defaults, without resolving a law (the calibration starts from the law as specified)
  std::vector<Override> defaults = {{"contact.calibration", "\"off\""}};
  if (!own_reference) {
    for (const ConfigSetting& s : kContactCalibrationReferenceMesh) defaults.push_back({s.key, s.value});
  }
  Config r = load_config("", defaults);
  r.contact_calibration = "auto";
  r.contact_law_resolution = {};
  r.file = c.file;  // relative mesh paths resolve against the config's folder
  r.implant_kind = c.implant_kind;
  r.femur_distal_radius_mm = c.femur_distal_radius_mm;
  r.femur_posterior_radius_mm = c.femur_posterior_radius_mm;
  r.femur_coronal_radius_mm = c.femur_coronal_radius_mm;
  r.condyle_width_mm = c.condyle_width_mm;
  r.condyle_spacing_mm = c.condyle_spacing_mm;
  r.insert_sagittal_radius_mm = c.insert_sagittal_radius_mm;
  r.insert_coronal_radius_mm = c.insert_coronal_radius_mm;
  r.insert_thickness_mm = c.insert_thickness_mm;
  r.insert_ap_depth_mm = c.insert_ap_depth_mm;
  r.insert_ml_width_mm = c.insert_ml_width_mm;
  r.femur_mesh = c.femur_mesh;
  r.insert_mesh = c.insert_mesh;
  r.mesh_units = c.mesh_units;
  r.mesh_rotation_deg = c.mesh_rotation_deg;
  r.mesh_left_knee = c.mesh_left_knee;
  r.femur_origin_mm = c.femur_origin_mm;
  r.insert_base_y_mm = c.insert_base_y_mm;
  r.articular_min_normal_y = c.articular_min_normal_y;
  r.insert_closed = c.insert_closed;
  r.material = c.material;
  r.user_materials = c.user_materials;
  r.contact_law = c.contact_law;
  r.threads = c.threads;  // results are bit-identical for any thread count
  if (!own_reference) return r;
  r.deformable_element_size_mm = c.deformable_element_size_mm;
  r.deformable_layers = c.deformable_layers;
  r.deformable_elements_across_contact = c.deformable_elements_across_contact;
  r.deformable_min_element_size_mm = c.deformable_min_element_size_mm;
  r.deformable_grading = c.deformable_grading;
  r.deformable_refine = c.deformable_refine;
  r.deformable_outer_element_size_mm = c.deformable_outer_element_size_mm;
  r.deformable_refine_margin_mm = c.deformable_refine_margin_mm;
  r.deformable_dt_us = c.deformable_dt_us;
  r.deformable_damping_per_s = c.deformable_damping_per_s;
  r.deformable_material = c.deformable_material;
  r.deformable_hardening_MPa = c.deformable_hardening_MPa;
  r.deformable_yield_cap_MPa = c.deformable_yield_cap_MPa;
  return r;
}

std::vector<std::string> calibration_unused_keys(const Config& config) {
  Config given = config;
  Config used = make_calibration_config(config, /*own_reference=*/true);
  using config_detail::Field, config_detail::Registry, config_detail::make_registry;
  const Registry a = make_registry(given), b = make_registry(used);
  std::vector<std::string> unused;
  for (const auto& [key, field] : a.fields()) {
    if (key == "contact.calibration") continue;  // the calibration sets it itself
    const Field* other = b.find(key);
    if (other && field.show && other->show && field.show() != other->show()) unused.push_back(key);
  }
  return unused;  // std::map order: sorted
}

}  // namespace kneesim::models
