#include "analysis/report/run_report.h"

#include <cmath>
#include <fstream>

#include "analysis/report/csv_columns.h"
#include "analysis/report/file_hash.h"
#include "analysis/report/report_page.h"
#include "analysis/report/svg_plot.h"

namespace kneesim::report {

void SceneRecorder::clear() {
  next_ = 0;
  pcts_.clear();
  pressure_Pa_.clear();
  X_TF_.clear();
}

void SceneRecorder::observe(const engine::Model& model, const engine::State&,
                            const engine::Data& data) {
  const double target = next_ * every_pct_;
  if (target >= 100.0 - 1e-9) return;
  double pct = data.gait_pct;
  // the first call of the last cycle may still read 99.99 % of the cycle before
  if (next_ == 0 && pct > 50.0) pct = 0.0;
  if (pct < target - 1e-9) return;
  pcts_.push_back(target);
  pressure_Pa_.push_back(model.insert_solid.empty() ? data.pressure
                                                    : std::vector<double>{});
  X_TF_.push_back(data.X_WT.inverse() * data.X_WF);
  ++next_;
}

SceneMesh insert_scene_mesh(const models::BuiltModel& built) {
  SceneMesh m;
  const models::TriMesh& t = built.implant.insert;
  if (!t.triangles.empty()) {
    for (const auto& v : t.vertices) m.vertices_mm.push_back(v * 1e3);
    m.triangles = t.triangles;
  } else {
    for (const auto& v : built.model.insert.vertices_T) m.vertices_mm.push_back(v * 1e3);
    m.triangles = built.model.insert.triangles;
  }
  return m;
}

SceneMesh femur_scene_mesh(const models::BuiltModel& built) {
  SceneMesh m;
  for (const auto& v : built.implant.femur.vertices) m.vertices_mm.push_back(v * 1e3);
  m.triangles = built.implant.femur.triangles;
  return m;
}

std::vector<double> to_insert_faces(const models::BuiltModel& built,
                                    const std::vector<double>& per_element, double scale) {
  const auto& map = built.implant.articular_to_insert;
  if (built.implant.insert.triangles.empty() || map.size() != per_element.size()) {
    std::vector<double> v(per_element);
    for (double& x : v) x *= scale;
    return v;
  }
  std::vector<double> faces(built.implant.insert.triangles.size(), std::nan(""));
  for (size_t e = 0; e < map.size(); ++e) faces[map[e]] = per_element[e] * scale;
  return faces;
}

Scene3D SceneRecorder::make_scene(const models::BuiltModel& built) const {
  Scene3D s;
  s.insert = insert_scene_mesh(built);
  if (pcts_.empty()) {
    // the CVODE reference integrator calls no observer: no instants were recorded
    s.step_values = {0.0};
    s.note = "The insert's geometry only: this integrator reports no per-step contact state "
             "(the pressure maps at output.map_pcts are in pressure_<pct>pct.vtp).";
    return s;
  }
  s.femur = femur_scene_mesh(built);
  s.step_values = pcts_;
  for (const auto& X : X_TF_) {
    Eigen::Isometry3d Y = X;
    Y.translation() *= 1e3;
    s.femur_pose_mm.push_back(Y);
  }
  const bool rigid = built.model.insert_solid.empty();
  if (rigid && !pressure_Pa_.empty()) {
    SceneField f{"contact pressure", "MPa", {}};
    double best = -1.0;
    for (size_t k = 0; k < pressure_Pa_.size(); ++k) {
      f.steps.push_back(to_insert_faces(built, pressure_Pa_[k], 1e-6));
      double m = 0.0;
      for (double p : pressure_Pa_[k]) m = std::max(m, p);
      if (m > best) {
        best = m;
        s.initial_step = static_cast<int>(k);  // open at the frame of the highest pressure
      }
    }
    s.fields.push_back(std::move(f));
  }
  s.note = std::string("New (unworn) insert. ") +
           (rigid ? "Contact pressure of every articular element at every 2 % of the last gait "
                    "cycle, the femoral component at the same instants; the slider opens at "
                    "the highest pressure. The maps at output.map_pcts are also in "
                    "pressure_<pct>pct.vtp (ParaView)."
                  : "Deformable insert: its node pressures and stresses are in "
                    "pressure_<pct>pct.vtp and insert_stress.vtu (ParaView); the view shows "
                    "the geometry and the femoral component at every 2 % of the last cycle.");
  return s;
}

namespace {

PlotSpec gait_plot(const std::string& title, const std::string& y_label, const CsvColumns& k,
                   const std::vector<std::pair<std::string, std::string>>& columns,
                   bool from_zero) {
  PlotSpec p;
  p.title = title;
  p.x_label = "gait cycle (%)";
  p.y_label = y_label;
  p.y_from_zero = from_zero;
  for (const auto& [col, name] : columns) {
    if (!k.has(col)) continue;
    p.series.push_back({name, k.col("gait_pct"), k.col(col), "", false, false});
  }
  return p;
}

}  // namespace

void write_run_report(const std::filesystem::path& out, const Provenance& provenance,
                      Scene3D scene) {
  nlohmann::json summary;
  {
    std::ifstream in(out / "summary.json");
    summary = nlohmann::json::parse(in);
  }
  const CsvColumns k = read_csv_columns(out / "kinematics.csv");
  auto text = [&summary](const char* key) {
    return summary.contains(key) && summary[key].is_string() ? summary[key].get<std::string>()
                                                             : std::string("?");
  };
  const int cycles = summary.value("cycles", 0);
  ReportPage page("kneesim run: " + text("material") + " insert, " + text("implant") +
                      " implant, " + text("rig_preset") + " rig",
                  "New (unworn) insert; results of the last of " + std::to_string(cycles) +
                      " gait cycle(s); contact law " + text("contact_law") + ", integrator " +
                      text("integrator") + ".");
  std::vector<KeyNumber> n;
  add_key_number(n, summary, "/ap_rom_mm", "AP range (tibia relative to femur)", "mm", 2);
  add_key_number(n, summary, "/ie_rom_deg", "IE range (tibia relative to femur)", "deg", 2);
  add_key_number(n, summary, "/peak_pressure_MPa", "peak contact pressure", "MPa", 1);
  add_key_number(n, summary, "/mean_peak_pressure_MPa", "frame peak pressure, mean in contact",
                 "MPa", 1);
  add_key_number(n, summary, "/peak_contact_force_N", "peak contact force", "N", 0);
  add_key_number(n, summary, "/peak_axial_load_N", "peak applied axial load", "N", 0);
  add_key_number(n, summary, "/medial_fraction_stance", "medial share of the load, 0-60 %", "%",
                 1, 100.0);
  add_key_number(n, summary, "/mean_contact_area_mm2", "contact area, mean in contact", "mm\u00b2",
                 1);
  add_key_number(n, summary, "/cycles", "gait cycles simulated", "", 0);
  add_key_number(n, summary, "/articular_elements", "articular elements", "", 0);
  add_key_number(n, summary, "/dt_s", "time step", "ms", 4, 1e3);
  add_key_number(n, summary, "/seconds_per_cycle", "wall time per cycle", "s", 3);
  page.add_numbers("Key numbers (summary.json)", n);
  page.set_scene(std::move(scene));

  // measured overlay
  CsvColumns measured;
  const bool have_measured = std::filesystem::exists(out / "measured_kinematics.csv");
  if (have_measured) measured = read_csv_columns(out / "measured_kinematics.csv");
  std::vector<PlotSpec> kin = {
      gait_plot("AP translation", "AP, tibia anterior (mm)", k, {{"ap_mm", "kneesim"}}, false),
      gait_plot("IE rotation", "IE, tibia internal (deg)", k, {{"ie_deg", "kneesim"}}, false),
      gait_plot("Flexion", "flexion (deg)", k, {{"flexion_deg", "kneesim"}}, false),
      gait_plot("ML translation and varus-valgus", "ML (mm), VV (deg)", k,
                {{"ml_mm", "ML (mm)"}, {"vv_deg", "VV (deg)"}}, false)};
  if (have_measured) {
    kin[0].series.push_back({"measured", measured.col("gait_pct"), measured.col("ap_mm"), "#000",
                             true, false});
    kin[1].series.push_back({"measured", measured.col("gait_pct"), measured.col("ie_deg"),
                             "#000", true, false});
  }
  page.add_plots("Kinematics: joint coordinates (tibia relative to femur)", kin,
                 "Last gait cycle, from kinematics.csv (one row per 1 % of the cycle).");
  PlotSpec loads = gait_plot("Axial load and contact force", "force (N)", k,
                             {{"axial_force_N", "applied axial load"},
                              {"contact_axial_force_N", "contact force, axial"}},
                             true);
  if (!loads.series.empty()) {
    loads.series[0].dashed = true;  // the contact force follows the load closely: both seen
    loads.series[0].colour = "#000";
  }
  page.add_plots(
      "Loads and contact",
      {loads,
       gait_plot("Contact pressure", "pressure (MPa)", k,
                 {{"peak_pressure_MPa", "peak"}, {"mean_pressure_MPa", "mean"}}, true),
       gait_plot("Contact area", "area (mm\u00b2)", k,
                 {{"contact_area_mm2", "total"},
                  {"medial_area_mm2", "medial"},
                  {"lateral_area_mm2", "lateral"}},
                 true),
       gait_plot("Condylar contact forces", "normal force (N)", k,
                 {{"medial_force_N", "medial"}, {"lateral_force_N", "lateral"}}, true)},
      "Last gait cycle, from kinematics.csv.");
  Provenance p = provenance;
  if (summary.contains("gait_file") && summary["gait_file"].is_string()) {
    const std::string gait = summary["gait_file"].get<std::string>();
    bool listed = false;
    for (const InputFile& f : p.inputs) listed = listed || f.path == gait;
    if (!listed) p.inputs.push_back({"gait waveform", gait, sha256_file(gait)});
  }
  page.set_provenance(std::move(p));
  write_report(out / "report.html", page);
}

}  // namespace kneesim::report
