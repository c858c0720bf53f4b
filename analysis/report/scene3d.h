// The 3D view of a report: the insert (T frame) and the femoral component (F frame, posed in T
// per slider step), the insert's triangles coloured by a field (contact pressure, wear depth,
// stress) at every slider step (gait %, wear update). Encoded for the page as JSON with
// base64 typed arrays; colours are quantised to one byte per triangle and step (255 = no
// value, e.g. a face outside the articular surface), the legend carries the exact range.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

namespace kneesim::report {

struct SceneMesh {
  std::vector<Eigen::Vector3d> vertices_mm;
  std::vector<Eigen::Vector3i> triangles;
  bool empty() const { return triangles.empty(); }
};

struct SceneField {
  std::string name;   // e.g. "contact pressure"
  std::string unit;   // e.g. "MPa"
  // per slider step, one value per insert triangle; NaN: no value (drawn grey)
  std::vector<std::vector<double>> steps;
};

struct Scene3D {
  SceneMesh insert;                    // T frame [mm]
  SceneMesh femur;                     // F frame [mm]; empty: not shown
  std::vector<Eigen::Isometry3d> femur_pose_mm;  // X_TF per step (translation in mm); one
                                                 // pose: the same at every step
  std::string step_name = "gait";      // slider label
  std::string step_unit = "%";
  std::vector<double> step_values;     // one per step
  int initial_step = 0;
  std::vector<SceneField> fields;
  std::string note;                    // shown under the view (what is drawn, e.g. "new insert")
  bool empty() const { return insert.empty(); }
};

// standard base64 (RFC 4648) of raw bytes
std::string base64(const void* data, size_t bytes);

// the scene as the page's JSON (throws std::logic_error for a field of the wrong size)
nlohmann::json scene_json(const Scene3D& scene);

}  // namespace kneesim::report
