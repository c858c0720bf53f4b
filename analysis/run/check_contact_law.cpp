#include "analysis/run/check_contact_law.h"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "analysis/run/calibrate_contact_law.h"
#include "analysis/run/contact_calibration.h"
#include "analysis/run/gait_run.h"
#include "engine/contact_law.h"
#include "engine/errors.h"
#include "engine/io/json_out.h"
#include "engine/io/output_folder.h"
#include "engine/io/plot.h"
#include "models/contact_law_key.h"
#include "models/contact_law_library.h"

namespace kneesim::run {
namespace {

struct RigidRun {
  PressureTrace trace;
  double seconds_per_cycle = 0.0;
  double foundation_modulus_MPa = 0.0;
};

RigidRun run_rigid(const models::Config& config, const std::filesystem::path& dir,
                   bool plots) {
  GaitRunJob run;
  run.config = config;
  run.out = dir;
  run.quiet = true;
  run.plots = plots;
  const GaitRunReport r = run_gait_job(run);
  return {read_pressure_trace(dir / "kinematics.csv"), r.seconds / config.cycles,
          r.summary.value("contact_foundation_modulus_MPa", 0.0)};
}

// the deformable insert of `c` is on the calibration's reference mesh (what the shipped and
// cached laws were fitted against): otherwise the check's differences include the mesh's
bool on_reference_mesh(const models::Config& c) {
  const models::Config r = models::make_calibration_config(c);
  return c.deformable_element_size_mm == r.deformable_element_size_mm &&
         c.deformable_layers == r.deformable_layers &&
         c.deformable_grading == r.deformable_grading &&
         c.deformable_refine == r.deformable_refine &&
         c.deformable_refine_margin_mm == r.deformable_refine_margin_mm &&
         c.deformable_outer_element_size_mm == r.deformable_outer_element_size_mm;
}

double relative(double value, double reference) {
  return reference != 0.0 ? value / reference - 1.0 : 0.0;
}

}  // namespace

nlohmann::json check_contact_law(const ContactLawCheckJob& job) {
  namespace fs = std::filesystem;
  const fs::path& out = job.out;
  if (job.config.insert_kind != "rigid" || job.specified.insert_kind != "rigid") {
    throw InputError("check-contact compares the rigid insert's contact law with the deformable "
                     "insert and runs both itself: insert = \"" + job.config.insert_kind +
                     "\" is not allowed (leave insert at \"rigid\").");
  }
  if (job.specified.contact_law_resolution.source != "specified") {
    throw std::invalid_argument("check_contact_law: the specified config resolves its law as \"" +
                                job.specified.contact_law_resolution.source + "\"");
  }
  io::check_output_folder(out);
  models::Config law = job.config;
  ensure_contact_law(law, job.quiet);  // first use: calibrated now (minutes), as any command does
  if (!job.quiet) {
    const auto& r = law.contact_law_resolution;
    std::fprintf(stderr, "check-contact: the law %s (%s%s%s); deformable insert, 1 cycle\n",
                 r.source == "specified" ? "as specified" : "used by every command",
                 r.source.c_str(), r.file.empty() ? "" : ", ", r.file.c_str());
  }

  const bool reference_mesh = on_reference_mesh(job.specified);
  if (!reference_mesh && !job.quiet) {
    std::fprintf(stderr, "check-contact: note: the deformable insert is not on the "
                 "calibration's reference mesh (0.5 mm where the contact occurs, 6 layers graded "
                 "0.15): the differences include the mesh's\n");
  }
  GaitRunJob deformable_run;
  deformable_run.config = job.specified;
  // on the surfaces the law was fitted against (its provenance: a stiff insert's reference is
  // on finer facets and distance field than a rigid run's, calibrate-contact's
  // --reference-edge-mm and --reference-sdf-mm), not the rigid runs' own
  for (const auto& [key, value] : law.contact_law_resolution.provenance) {
    const double v = std::strtod(value.c_str(), nullptr);
    if (!(v > 0.0)) continue;
    if (key == "reference_edge_length_mm" && law.implant_kind == "generic") {
      deformable_run.config.edge_length_mm = v;
    } else if (key == "reference_sdf_spacing_mm") {
      deformable_run.config.sdf_spacing_mm = v;
    }
  }
  const bool own_surfaces = deformable_run.config.edge_length_mm == law.edge_length_mm &&
                            deformable_run.config.sdf_spacing_mm == law.sdf_spacing_mm;
  if (!own_surfaces && !job.quiet) {
    std::fprintf(stderr, "check-contact: the deformable insert on the law's reference surfaces: "
                 "%g mm facets, distance field %g mm (the rigid runs: %g mm, %g mm)\n",
                 deformable_run.config.edge_length_mm, deformable_run.config.sdf_spacing_mm,
                 law.edge_length_mm, law.sdf_spacing_mm);
  }
  deformable_run.config.insert_kind = "deformable";
  deformable_run.config.cycles = 1;
  models::resolve_contact_law(deformable_run.config);  // "unused"
  deformable_run.out = out / "deformable";
  deformable_run.quiet = job.quiet;
  deformable_run.plots = job.plots;
  const GaitRunReport d = run_gait_job(deformable_run);
  const PressureTrace deformable = read_pressure_trace(deformable_run.out / "kinematics.csv");
  if (!job.quiet) std::fprintf(stderr, "check-contact: rigid insert, the law and as specified\n");
  const RigidRun with_law = run_rigid(law, out / "rigid_law", job.plots);
  const RigidRun specified = run_rigid(job.specified, out / "rigid", job.plots);

  nlohmann::json s;
  s["material"] = law.material.name;
  s["implant"] = models::implant_identity(law);
  s["rig_preset"] = law.rig_preset;
  s["gait_file"] = law.gait_file;
  s["gait_period_s"] = law.period_s;
  s["contact_law"] = describe_contact_law(law, with_law.foundation_modulus_MPa);
  s["specified_modulus_MPa"] = engine::foundation_modulus(law.material.elastic_modulus_MPa,
                                                          law.material.poisson);
  s["deformable_elements"] = d.summary.value("solid_elements", 0);
  s["deformable_element_size_mm"] = job.specified.deformable_element_size_mm;
  s["deformable_refine"] = job.specified.deformable_refine;
  s["deformable_on_reference_mesh"] = reference_mesh;
  s["deformable_sdf_spacing_mm"] = deformable_run.config.sdf_spacing_mm;
  s["rigid_sdf_spacing_mm"] = law.sdf_spacing_mm;
  if (law.implant_kind == "generic") {
    s["deformable_implant_edge_length_mm"] = deformable_run.config.edge_length_mm;
    s["rigid_implant_edge_length_mm"] = law.edge_length_mm;
  }
  add_window_errors(s, "rigid_as_specified", specified.trace, deformable);
  add_window_errors(s, "rigid_law", with_law.trace, deformable);
  const WindowFigures fd =
      calc_window_figures(deformable, kStanceLo, kStanceHi);
  const WindowFigures fl =
      calc_window_figures(with_law.trace, kStanceLo, kStanceHi);
  const WindowFigures fs_ =
      calc_window_figures(specified.trace, kStanceLo, kStanceHi);
  s["stance_figures"] = {{"deformable", window_figures_json(fd)},
                         {"rigid_law", window_figures_json(fl)},
                         {"rigid_as_specified", window_figures_json(fs_)}};
  // the differences a designer reads: each law's stance figure against the deformable insert's
  for (const auto& [name, f] : {std::pair{"rigid_law", fl}, std::pair{"rigid_as_specified", fs_}}) {
    s["stance_difference"][name] = {{"peak", relative(f.peak_MPa, fd.peak_MPa)},
                                    {"mean_peak", relative(f.mean_peak_MPa, fd.mean_peak_MPa)},
                                    {"mean", relative(f.mean_MPa, fd.mean_MPa)},
                                    {"area", relative(f.area_mm2, fd.area_mm2)}};
  }
  s["seconds_per_cycle"] = {{"deformable", d.seconds},
                            {"rigid_law", with_law.seconds_per_cycle},
                            {"rigid_as_specified", specified.seconds_per_cycle}};
  write_pressure_comparison(out / "comparison.csv", deformable, specified.trace, with_law.trace);
  io::write_json(out / "summary.json", s);
  if (job.plots) {
    io::run_plot("calibrate.py", {(out / "comparison.csv").string(),
                                  (out / "calibration.png").string(),
                                  law.material.name + ", rig " + law.rig_preset, "check"});
  }
  return s;
}

}  // namespace kneesim::run
