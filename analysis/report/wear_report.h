// The reports of `kneesim wear` and `kneesim compare` (DIR/report.html): key numbers read back
// from the command's own summary (DIR/summary.json, DIR/comparison.json), the wear curves from
// DIR/wear.csv, the final (worn) cycle's kinematics from DIR/kinematics.csv, and a 3D view of
// the pristine insert coloured by the wear depth after every geometry update (recorded during
// the run; the same depths as DIR/wear_depth_<cycles>.vtp). For compare, each material's depth
// is a colour choice of one view and every plot shows the materials side by side.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "analysis/report/provenance.h"
#include "analysis/report/scene3d.h"
#include "engine/simulate.h"
#include "models/build_model.h"

namespace kneesim::report {

// the wear depth per wear site after each update, as the wear loop reports it
class WearSceneRecorder {
 public:
  void add(double cycles, const std::vector<double>& site_depth_m);
  // the pristine insert with one field "wear depth" (mm) per recorded update, the femoral
  // component at the final cycle's peak axial load; `label` names the material in the field
  Scene3D make_scene(const models::BuiltModel& built, const std::vector<engine::Frame>& frames,
                     const std::string& label) const;

 private:
  std::vector<double> cycles_;
  std::vector<std::vector<double>> depth_;
};

void write_wear_report(const std::filesystem::path& out, const Provenance& provenance,
                       Scene3D scene);

// `materials` in the order run; `scenes` one per material (same insert and updates), may be
// empty (no 3D view)
void write_compare_report(const std::filesystem::path& out, const Provenance& provenance,
                          const std::vector<std::string>& materials,
                          const std::vector<Scene3D>& scenes);

}  // namespace kneesim::report
