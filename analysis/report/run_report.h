// The report of `kneesim run` (DIR/report.html): the key numbers and the kinematics and contact
// plots read back from the run's own DIR/summary.json and DIR/kinematics.csv (so the page shows
// what the files say), and the 3D view: the insert coloured by contact pressure with the
// femoral component posed at every 2 % of the last cycle (recorded during the run).
#pragma once

#include <filesystem>
#include <vector>

#include "analysis/report/provenance.h"
#include "analysis/report/scene3d.h"
#include "engine/data.h"
#include "engine/model.h"
#include "engine/state.h"
#include "models/build_model.h"

namespace kneesim::report {

// records the contact pressure and the femoral pose at every `every_pct` of the last cycle
// (an engine observer: simulate() calls it after every step of the last cycle)
class SceneRecorder {
 public:
  explicit SceneRecorder(double every_pct = 2.0) : every_pct_(every_pct) {}
  void clear();  // before a retried attempt
  void observe(const engine::Model& model, const engine::State& state, const engine::Data& data);
  // the insert (the implant's whole mesh, articular faces coloured), the femoral component and
  // the recorded steps
  Scene3D make_scene(const models::BuiltModel& built) const;

 private:
  double every_pct_;
  int next_ = 0;
  std::vector<double> pcts_;
  std::vector<std::vector<double>> pressure_Pa_;  // per step, per articular element
  std::vector<Eigen::Isometry3d> X_TF_;
};

// the insert and femoral meshes of a built model in mm, for a scene
SceneMesh insert_scene_mesh(const models::BuiltModel& built);
SceneMesh femur_scene_mesh(const models::BuiltModel& built);
// one value per articular element -> one per insert-mesh face (NaN off the articular surface)
std::vector<double> to_insert_faces(const models::BuiltModel& built,
                                    const std::vector<double>& per_element, double scale);

// writes out/report.html from out/summary.json and out/kinematics.csv (the measured overlay
// out/measured_kinematics.csv when present)
void write_run_report(const std::filesystem::path& out, const Provenance& provenance,
                      Scene3D scene);

}  // namespace kneesim::report
