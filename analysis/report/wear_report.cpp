#include "analysis/report/wear_report.h"

#include <cmath>
#include <cstdio>
#include <fstream>

#include "analysis/report/csv_columns.h"
#include "analysis/report/report_page.h"
#include "analysis/report/run_report.h"
#include "analysis/report/svg_plot.h"
#include "engine/kinematics.h"

namespace kneesim::report {

void WearSceneRecorder::add(double cycles, const std::vector<double>& site_depth_m) {
  if (!cycles_.empty() && cycles <= cycles_.back()) return;  // a repeated record
  cycles_.push_back(cycles);
  depth_.push_back(site_depth_m);
}

Scene3D WearSceneRecorder::make_scene(const models::BuiltModel& built,
                                      const std::vector<engine::Frame>& frames,
                                      const std::string& label) const {
  Scene3D s;
  s.insert = insert_scene_mesh(built);
  s.femur = femur_scene_mesh(built);
  s.step_name = "cycles";
  s.step_unit = "";
  s.step_values = cycles_;
  s.initial_step = static_cast<int>(cycles_.size()) - 1;
  // the femoral component at the final cycle's peak axial load
  size_t peak = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    if (-frames[i].applied[0][1] > -frames[peak].applied[0][1]) peak = i;
  }
  if (!frames.empty()) {
    const engine::Model& m = built.model;
    Eigen::Isometry3d X = engine::calc_part_pose(m.carriages[1], frames[peak].q[1]).inverse() *
                          engine::calc_part_pose(m.carriages[0], frames[peak].q[0]);
    X.translation() *= 1e3;
    s.femur_pose_mm.push_back(X);
  } else {
    s.femur = {};
  }
  const bool rigid = built.model.insert_solid.empty();
  const engine::InsertSurface& a = built.model.insert;
  if (rigid && !depth_.empty() && depth_.front().size() == a.vertices_T.size()) {
    SceneField f{label.empty() ? "wear depth" : "wear depth, " + label, "mm", {}};
    for (const auto& d : depth_) {
      std::vector<double> per_element(a.triangles.size());
      for (size_t e = 0; e < a.triangles.size(); ++e) {
        const auto& t = a.triangles[e];
        per_element[e] = (d[t[0]] + d[t[1]] + d[t[2]]) / 3.0;
      }
      f.steps.push_back(to_insert_faces(built, per_element, 1e3));
    }
    s.fields.push_back(std::move(f));
    s.note = "Pristine insert geometry coloured by the wear depth accumulated up to each "
             "geometry update (mean of each articular triangle's vertices; the same depths as "
             "wear_depth_<cycles>.vtp), the femoral component at the final cycle's peak axial "
             "load.";
  } else {
    s.note = rigid ? "The wear depth was not recorded in this process (a resumed run shows "
                     "the updates it ran)."
                   : "Deformable insert: its worn surface and stresses are in "
                     "wear_surface.vtp and insert_stress.vtu (ParaView).";
  }
  return s;
}

namespace {

std::string fmt_cycles(double c) {
  char b[32];
  std::snprintf(b, sizeof b, "%.0f", c);
  std::string s = b, o;
  for (size_t i = 0; i < s.size(); ++i) {
    if (i && (s.size() - i) % 3 == 0) o += "\u2009";  // thin space between thousands
    o += s[i];
  }
  return o;
}

nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream in(p);
  if (!in) throw std::runtime_error("the report cannot read " + p.string());
  return nlohmann::json::parse(in);
}

std::string text_of(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : std::string("?");
}

std::vector<double> to_mc(const std::vector<double>& cycles) {
  std::vector<double> v(cycles);
  for (double& c : v) c *= 1e-6;
  return v;
}

PlotSpec update_plot(const std::string& title, const std::string& y_label,
                     const std::vector<std::pair<const CsvColumns*, std::string>>& tables,
                     const std::vector<std::pair<std::string, std::string>>& columns,
                     bool from_zero) {
  PlotSpec p;
  p.title = title;
  p.x_label = "cycles (millions)";
  p.y_label = y_label;
  p.y_from_zero = from_zero;
  for (const auto& [t, prefix] : tables) {
    for (const auto& [col, name] : columns) {
      if (!t->has(col)) continue;
      const std::string label = prefix.empty() ? name : name.empty() ? prefix : prefix + ", " + name;
      p.series.push_back({label, to_mc(t->col("cycles")), t->col(col), "", false, true});
    }
  }
  return p;
}

PlotSpec gait_plot(const std::string& title, const std::string& y_label,
                   const std::vector<std::pair<const CsvColumns*, std::string>>& tables,
                   const std::string& col) {
  PlotSpec p;
  p.title = title;
  p.x_label = "gait cycle (%)";
  p.y_label = y_label;
  for (const auto& [t, name] : tables) {
    if (t->has(col)) p.series.push_back({name, t->col("gait_pct"), t->col(col), "", false, false});
  }
  return p;
}

void wear_numbers(std::vector<KeyNumber>& n, const nlohmann::json& s, const std::string& at) {
  add_key_number(n, s, at + "/volume_mm3", "volume loss", "mm\u00b3", 2);
  add_key_number(n, s, at + "/mass_mg", "mass loss", "mg", 2);
  add_key_number(n, s, at + "/wear_rate_mm3_per_Mc", "wear rate", "mm\u00b3/Mc", 2);
  add_key_number(n, s, at + "/max_depth_mm", "maximum linear wear depth", "mm", 3);
  add_key_number(n, s, at + "/medial_volume_mm3", "medial volume", "mm\u00b3", 2);
  add_key_number(n, s, at + "/lateral_volume_mm3", "lateral volume", "mm\u00b3", 2);
  add_key_number(n, s, at + "/peak_pressure_MPa", "peak pressure, new insert", "MPa", 1);
  add_key_number(n, s, at + "/contact_area_mm2", "contact area, new insert (mean)", "mm\u00b2", 1);
  add_key_number(n, s, at + "/ap_rom_mm", "AP range, new insert", "mm", 2);
  add_key_number(n, s, at + "/final_ap_rom_mm", "AP range, worn insert", "mm", 2);
  add_key_number(n, s, at + "/ie_rom_deg", "IE range, new insert", "deg", 2);
  add_key_number(n, s, at + "/final_ie_rom_deg", "IE range, worn insert", "deg", 2);
  add_key_number(n, s, at + "/wear_potential_Nmm", "wear potential per cycle, new", "N\u00b7mm", 0);
  add_key_number(n, s, at + "/wear_factor_mm3_per_Nmm", "wear factor",
                 "\u00d710\u207b\u00b9\u2070 mm\u00b3/(N\u00b7mm)", 3, 1e10);
  add_key_number(n, s, at + "/updates", "geometry updates", "", 0);
  add_key_number(n, s, at + "/seconds", "wall time", "s", 1);
}

}  // namespace

void write_wear_report(const std::filesystem::path& out, const Provenance& provenance,
                       Scene3D scene) {
  const nlohmann::json s = read_json(out / "summary.json");
  const CsvColumns w = read_csv_columns(out / "wear.csv");
  const double cycles = s.value("cycles", 0.0);
  const std::string material = text_of(s, "material");
  ReportPage page("kneesim wear: " + material + " insert, " + fmt_cycles(cycles) + " cycles, " +
                      text_of(s, "implant") + " implant, " + text_of(s, "rig_preset") + " rig",
                  std::to_string(s.value("updates", 0)) + " geometry updates; wear law " +
                      text_of(s, "wear_law") + "; wear factor: " +
                      text_of(s, "wear_factor_source") +
                      (s.value("wear_factor_independent", true)
                           ? ""
                           : " (not independent of kneesim's comparisons)") +
                      ".");
  std::vector<KeyNumber> n;
  wear_numbers(n, s, "");
  page.add_numbers("Key numbers (summary.json)", n);
  page.set_scene(std::move(scene));
  const std::vector<std::pair<const CsvColumns*, std::string>> one = {{&w, ""}};
  page.add_plots(
      "Wear over the cycles",
      {update_plot("Volume loss", "volume (mm\u00b3)", one,
                   {{"volume_mm3", "total"}, {"medial_volume_mm3", "medial"},
                    {"lateral_volume_mm3", "lateral"}},
                   true),
       update_plot("Maximum linear wear depth", "depth (mm)", one, {{"max_depth_mm", ""}}, true),
       update_plot("Contact pressure of each update's cycle", "pressure (MPa)", one,
                   {{"peak_pressure_MPa", "peak"}, {"mean_peak_pressure_MPa", "mean of peaks"}},
                   true),
       update_plot("Contact area of each update's cycle", "mean area in contact (mm\u00b2)", one,
                   {{"contact_area_mm2", ""}}, true),
       update_plot("Kinematic ranges of each update's cycle", "AP (mm), IE (deg)", one,
                   {{"ap_rom_mm", "AP range (mm)"}, {"ie_rom_deg", "IE range (deg)"}}, true)},
      "One point per geometry update (wear.csv); the first is the new insert.");
  if (std::filesystem::exists(out / "kinematics.csv")) {
    const CsvColumns k = read_csv_columns(out / "kinematics.csv");
    const std::vector<std::pair<const CsvColumns*, std::string>> kk = {{&k, ""}};
    page.add_plots("Kinematics of the final cycle, worn insert: joint coordinates (tibia "
                   "relative to femur)",
                   {gait_plot("AP translation, worn insert", "AP, tibia anterior (mm)", kk, "ap_mm"),
                    gait_plot("IE rotation, worn insert", "IE, tibia internal (deg)", kk, "ie_deg"),
                    gait_plot("Peak contact pressure, worn insert", "pressure (MPa)", kk,
                              "peak_pressure_MPa"),
                    gait_plot("Contact area, worn insert", "area (mm\u00b2)", kk,
                              "contact_area_mm2")},
                   "The gait cycle simulated on the final geometry (kinematics.csv).");
  }
  page.set_provenance(provenance);
  write_report(out / "report.html", page);
}

void write_compare_report(const std::filesystem::path& out, const Provenance& provenance,
                          const std::vector<std::string>& materials,
                          const std::vector<Scene3D>& scenes) {
  const nlohmann::json all = read_json(out / "comparison.json");
  std::vector<CsvColumns> wear, kin;
  for (const std::string& m : materials) {
    wear.push_back(read_csv_columns(out / m / "wear.csv"));
    kin.push_back(std::filesystem::exists(out / m / "kinematics.csv")
                      ? read_csv_columns(out / m / "kinematics.csv")
                      : CsvColumns{});
  }
  const nlohmann::json& first = all[materials.front()];
  std::string names;
  for (const auto& m : materials) names += (names.empty() ? "" : ", ") + m;
  ReportPage page("kneesim compare: " + names + ", " + fmt_cycles(first.value("cycles", 0.0)) +
                      " cycles",
                  "The same implant (" + text_of(first, "implant") + "), rig (" +
                      text_of(first, "rig_preset") + ") and gait for every material; " +
                      std::to_string(first.value("updates", 0)) + " geometry updates; wear law " +
                      text_of(first, "wear_law") + ".");
  std::vector<std::vector<KeyNumber>> columns;
  std::string dependent;
  for (const std::string& m : materials) {
    columns.emplace_back();
    wear_numbers(columns.back(), all, "/" + m);
    if (!all[m].value("wear_factor_independent", true)) {
      dependent += (dependent.empty() ? "" : ", ") + m;
    }
  }
  page.add_number_table(
      "Key numbers side by side (comparison.json)", materials, columns,
      "New insert: the pristine cycle's figures; worn insert: the cycle on the final geometry." +
          (dependent.empty()
               ? std::string()
               : " The wear factor of " + dependent +
                     " is not independent of kneesim's comparisons: its volume is not a "
                     "prediction (see the break-even ratios)."));
  if (!scenes.empty() && !scenes.front().empty()) {
    Scene3D s = scenes.front();
    s.fields.clear();
    for (const Scene3D& m : scenes) {
      for (const SceneField& f : m.fields) {
        if (f.steps.size() == s.step_values.size()) s.fields.push_back(f);
      }
    }
    s.note = "Each material's wear depth on the pristine insert after each geometry update "
             "(choose the material under 'colour by'; one colour scale per material, its range "
             "under the bar); the femoral component at the first material's final-cycle peak "
             "axial load.";
    page.set_scene(std::move(s));
  }
  std::vector<std::pair<const CsvColumns*, std::string>> wt, kt;
  for (size_t i = 0; i < materials.size(); ++i) {
    wt.push_back({&wear[i], materials[i]});
    if (kin[i].rows) kt.push_back({&kin[i], materials[i]});
  }
  page.add_plots("Materials side by side: wear",
                 {update_plot("Volume loss", "volume (mm\u00b3)", wt, {{"volume_mm3", ""}}, true),
                  update_plot("Maximum linear wear depth", "depth (mm)", wt,
                              {{"max_depth_mm", ""}}, true),
                  update_plot("Peak contact pressure of each update's cycle", "pressure (MPa)", wt,
                              {{"peak_pressure_MPa", ""}}, true),
                  update_plot("Contact area of each update's cycle", "area (mm\u00b2)", wt,
                              {{"contact_area_mm2", ""}}, true)},
                 "One point per geometry update (<material>/wear.csv); the first is the new "
                 "insert.");
  if (!kt.empty()) {
    page.add_plots(
        "Materials side by side: final cycle, worn insert (joint coordinates, tibia relative "
        "to femur)",
        {gait_plot("AP translation, worn insert", "AP, tibia anterior (mm)", kt, "ap_mm"),
         gait_plot("IE rotation, worn insert", "IE, tibia internal (deg)", kt, "ie_deg"),
         gait_plot("Peak contact pressure, worn insert", "pressure (MPa)", kt,
                   "peak_pressure_MPa"),
         gait_plot("Contact area, worn insert", "area (mm\u00b2)", kt, "contact_area_mm2")},
        "The gait cycle simulated on each material's final geometry (<material>/kinematics.csv).");
  }
  if (std::filesystem::exists(out / "break_even.csv")) {
    const CsvColumns be = read_csv_columns(out / "break_even.csv");
    TableBlock t;
    t.header = be.names;
    for (size_t r = 0; r < be.rows; ++r) {
      std::vector<std::string> row;
      for (const auto& c : be.names) row.push_back(be.text.at(c)[r]);
      t.rows.push_back(row);
    }
    page.add_table("Break-even wear-factor ratios (break_even.csv)", t,
                   "The ratio of a material's wear factor to the reference's at which it wears "
                   "the same volume (or maximum depth) over the run; comparison.md sets them "
                   "beside the published ranges.");
  } else if (all.contains("break_even") && all["break_even"].is_string()) {
    page.add_text("Break-even wear-factor ratios", all["break_even"].get<std::string>());
  }
  page.set_provenance(provenance);
  write_report(out / "report.html", page);
}

}  // namespace kneesim::report
