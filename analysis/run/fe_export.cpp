#include "analysis/run/fe_export.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/errors.h"

namespace kneesim::run {
namespace {

constexpr double kMm = 1e3;    // m -> mm
constexpr double kMPa = 1e-6;  // Pa -> MPa

nlohmann::json points_mm(const std::vector<Eigen::Vector3d>& p) {
  nlohmann::json a = nlohmann::json::array();
  for (const Eigen::Vector3d& v : p) a.push_back({v.x() * kMm, v.y() * kMm, v.z() * kMm});
  return a;
}

// a 4x4 homogeneous transform, rows, translation in mm
nlohmann::json pose_mm(const Eigen::Isometry3d& X) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) {
    rows.push_back({X.linear()(r, 0), X.linear()(r, 1), X.linear()(r, 2),
                    X.translation()(r) * kMm});
  }
  rows.push_back({0.0, 0.0, 0.0, 1.0});
  return rows;
}

}  // namespace

std::vector<double> find_heel_strike_and_load_peaks(const engine::Waveform& gait) {
  const int axial = gait.channel("axial_force_N");
  if (axial < 0) {
    throw InputError("FE export: the gait waveform (" + gait.source() +
                     ") has no axial_force_N channel to find the load peaks in");
  }
  // local maxima of the axial force on a 0.1 % grid (periodic)
  constexpr int kSamples = 1000;
  std::vector<double> f(kSamples);
  for (int i = 0; i < kSamples; ++i) f[i] = gait.value(axial, 100.0 * i / kSamples);
  std::vector<std::pair<double, double>> peaks;  // (force, pct)
  for (int i = 0; i < kSamples; ++i) {
    const double prev = f[(i + kSamples - 1) % kSamples], next = f[(i + 1) % kSamples];
    if (f[i] > prev && f[i] >= next) peaks.emplace_back(f[i], 100.0 * i / kSamples);
  }
  if (peaks.size() < 2) {
    throw InputError("FE export: the axial force of the gait waveform (" + gait.source() +
                     ") has " + std::to_string(peaks.size()) +
                     " local maxima; heel strike and two load peaks need at least 2");
  }
  std::sort(peaks.begin(), peaks.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<double> pcts = {peaks[0].second, peaks[1].second};
  std::sort(pcts.begin(), pcts.end());
  if (pcts.front() > 0.0) pcts.insert(pcts.begin(), 0.0);
  return pcts;
}

FeExportRecorder::FeExportRecorder(const engine::Model& model, std::vector<double> pcts)
    : pcts_(std::move(pcts)) {
  if (model.insert_solid.empty()) {
    throw InputError("FE export: the insert is rigid; the export needs insert = \"deformable\"");
  }
  std::sort(pcts_.begin(), pcts_.end());
  for (double p : pcts_) {
    if (!(p >= 0.0 && p < 100.0)) {
      throw InputError("FE export: gait instant " + std::to_string(p) +
                       " % is out of range (must be in [0, 100))");
    }
  }
}

void FeExportRecorder::observe(const engine::Model& model, const engine::State& state,
                               const engine::Data& data) {
  if (complete()) return;
  // data describes the start of the step just taken
  const double t = state.time - model.dt;
  // the observer's first call is the last cycle's first step (within half a step)
  if (!started_) {
    last_start_ = model.period * std::round(t / model.period);
    started_ = true;
  }
  const double local = t - last_start_;
  const double pct = pcts_[instants_.size()];
  if (local < pct / 100.0 * model.period - 0.5 * model.dt) return;

  const engine::solid::SolidModel& solid = model.insert_solid;
  const engine::solid::SolidState& s = state.insert_solid;
  const engine::solid::SurfaceContact& contact = model.insert_contact;
  const engine::solid::SurfaceContactData& out = data.insert_contact;
  const engine::ContactSummary& sum = data.contact;
  nlohmann::json j;
  j["gait_pct_requested"] = pct;
  j["gait_pct"] = std::max(0.0, 100.0 * local / model.period);
  j["time_s"] = t;
  // the femoral component's pose in the insert frame: x_T = X_TF x_F
  j["X_TF_mm"] = pose_mm(data.X_WT.inverse() * data.X_WF);
  // the force of the femur on the insert, in T [N]
  const Eigen::Vector3d force_T = -(data.X_WT.linear().transpose() * sum.force_W);
  j["contact_force_on_insert_T_N"] = {force_T.x(), force_T.y(), force_T.z()};
  // the femoral IS DOF carries the axial load, negative downwards (models/build_model.cpp)
  j["applied_axial_force_N"] = -data.applied[0][1];
  // per top node (model.insert_contact order)
  nlohmann::json pressure = nlohmann::json::array();
  for (int i = 0; i < contact.size(); ++i) pressure.push_back(out.pressure[i] * kMPa);
  j["top_node_pressure_MPa"] = std::move(pressure);
  nlohmann::json von_mises = nlohmann::json::array(), plastic = nlohmann::json::array();
  for (int e = 0; e < solid.num_elements(); ++e) {
    von_mises.push_back(data.insert_solid.von_mises[e] * kMPa);
    plastic.push_back(s.alpha[e]);
  }
  j["element_von_mises_MPa"] = std::move(von_mises);
  j["element_plastic_strain"] = std::move(plastic);
  // node positions at t: the last central-difference update undone
  std::vector<Eigen::Vector3d> x(solid.num_nodes());
  for (int n = 0; n < solid.num_nodes(); ++n) x[n] = s.position[n] - model.dt * s.velocity[n];
  j["node_position_mm"] = points_mm(x);
  // kneesim's own contact summary at that step (medial: z < 0 in T)
  j["summary"] = {{"peak_pressure_MPa", sum.peak_pressure * kMPa},
                  {"mean_pressure_MPa", sum.mean_pressure * kMPa},
                  {"contact_area_mm2", (sum.area[0] + sum.area[1]) * 1e6},
                  {"medial_force_N", sum.normal_force[0]},
                  {"lateral_force_N", sum.normal_force[1]},
                  {"medial_area_mm2", sum.area[0] * 1e6},
                  {"lateral_area_mm2", sum.area[1] * 1e6},
                  {"nodes_in_contact", sum.elements_in_contact}};
  instants_.push_back(std::move(j));
}

nlohmann::json make_fe_export(const models::BuiltModel& built, const models::Config& config,
                              const FeExportRecorder& recorder) {
  const engine::Model& model = built.model;
  const engine::solid::SolidModel& solid = model.insert_solid;
  const engine::solid::SurfaceContact& contact = model.insert_contact;
  nlohmann::json j;
  j["format"] = "kneesim FE export 1";
  j["units"] = "mm, N, MPa; frames: T (insert; y up, z < 0 medial), F (femoral component)";
  j["implant"] = config.implant_kind == "mesh"
                     ? nlohmann::json{{"femur_mesh", config.femur_mesh},
                                      {"insert_mesh", config.insert_mesh}}
                     : nlohmann::json("generic");
  j["mesh"] = {{"element_size_mm", config.deformable_element_size_mm},
               {"layers", config.deformable_layers},
               {"grading", config.deformable_grading},
               {"nodes_mm", points_mm(solid.reference_positions)},
               {"elements", solid.elements},
               {"top_faces", model.insert_top_faces},
               {"top_face_element", model.insert_top_face_element},
               {"base_nodes", model.insert_base_nodes}};
  nlohmann::json area = nlohmann::json::array(), stiffness = nlohmann::json::array();
  for (int i = 0; i < contact.size(); ++i) {
    area.push_back(contact.area[i] * 1e6);
    stiffness.push_back(contact.stiffness[i] * 1e-3);  // N/m -> N/mm
  }
  j["contact"] = {{"top_nodes", contact.nodes},
                  {"tributary_area_mm2", std::move(area)},
                  {"penalty_N_per_mm", std::move(stiffness)},
                  {"friction", contact.friction},
                  {"law", "node-to-surface penalty p = k_n (-phi) / A_n against the femur's "
                          "signed distance field"},
                  {"sdf_spacing_mm", config.sdf_spacing_mm}};
  const engine::solid::SolidMaterial& m = solid.material;
  j["material"] = {
      {"name", config.material.name},
      {"model", m.kind == engine::solid::SolidMaterialKind::kElastic ? "elastic" : "j2"},
      {"youngs_modulus_MPa", m.youngs_modulus * kMPa},
      {"poisson", m.poisson},
      {"yield_MPa", m.yield_stress * kMPa},
      {"hardening_MPa", m.hardening_modulus * kMPa},
      {"yield_cap_MPa", m.yield_cap * kMPa}};
  nlohmann::json triangles = nlohmann::json::array();
  for (const Eigen::Vector3i& t : built.implant.femur.triangles) triangles.push_back({t[0], t[1], t[2]});
  j["femur"] = {{"vertices_F_mm", points_mm(built.implant.femur.vertices)},
                {"triangles", std::move(triangles)},
                {"orientation", "counter-clockwise seen from outside"}};
  j["instants"] = recorder.instants();
  return j;
}

}  // namespace kneesim::run
