// `kneesim implant check CONFIG`: loads the implant meshes exactly as a run does (so every
// refusal of a run is reproduced here, exit 2), then prints what the run will use (units,
// sizes, the insert's articular area and its medial/lateral split, the flexion axis, the gaps
// between the components) with warnings about the frame, and writes DIR/implant_check.json and
// DIR/implant_views.png (front, side and top views of the femur over the insert as the run
// starts, with the axes). The checks are library calls (models/implant_check.h).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "analysis/report/file_hash.h"
#include "analysis/run/gait_run.h"
#include "engine/errors.h"
#include "engine/io/json_out.h"
#include "engine/io/output_folder.h"
#include "engine/io/plot.h"
#include "models/build_model.h"
#include "models/implant_check.h"
#include "models/mesh_io.h"
#include "tools/kneesim/commands.h"

namespace kneesim::cli {
namespace {

struct ImplantArgs {
  std::string config;
  std::string out = "kneesim-implant";
  std::vector<std::string> sets;
  bool no_plots = false;
};

nlohmann::json to_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

void check(const ImplantArgs& a) {
  namespace fs = std::filesystem;
  const models::Config config = run::load_run_config(a.config, a.sets);
  io::check_output_folder(a.out);
  const models::Implant implant = models::load_implant(config);  // refusals: InputError
  const engine::InsertSurface surface =
      models::make_insert_surface(implant.insert, 0.0, config.articular_min_normal_y, nullptr,
                                  nullptr);
  if (surface.size() == 0) {
    throw InputError((config.file.empty() ? std::string("built-in config") : config.file.string()) +
                     ": the insert has no articular faces (implant.mesh.articular_min_normal_y = " +
                     std::to_string(config.articular_min_normal_y) +
                     "; allowed: below the largest face normal y)");
  }
  const models::ImplantFacts f = models::describe_implant(config, implant, surface);
  const bool mesh = config.implant_kind == "mesh";

  // the terminal report
  std::printf("implant: %s\n", mesh ? "meshes" : "built-in generic TKR (implant.kind = \"generic\")");
  if (mesh) {
    std::printf("  femur  %s\n  insert %s\n  units %s, rotation_deg [%g, %g, %g]%s\n",
                models::resolve_path(config, config.femur_mesh).string().c_str(),
                models::resolve_path(config, config.insert_mesh).string().c_str(),
                config.mesh_units.c_str(), config.mesh_rotation_deg[0],
                config.mesh_rotation_deg[1], config.mesh_rotation_deg[2],
                config.mesh_left_knee ? ", left knee mirrored" : "");
  }
  const Eigen::Vector3d fs_mm = f.femur_max_mm - f.femur_min_mm;
  const Eigen::Vector3d is_mm = f.insert_max_mm - f.insert_min_mm;
  std::printf("frame: +x anterior, +y superior, +z lateral (project frame, mm)\n");
  std::printf("femur:  %d triangles, %s, size AP %.1f x SI %.1f x ML %.1f mm, x %.1f..%.1f, "
              "y %.1f..%.1f, z %.1f..%.1f\n",
              f.femur_triangles, f.femur_closed ? "closed" : "open", fs_mm.x(), fs_mm.y(),
              fs_mm.z(), f.femur_min_mm.x(), f.femur_max_mm.x(), f.femur_min_mm.y(),
              f.femur_max_mm.y(), f.femur_min_mm.z(), f.femur_max_mm.z());
  std::printf("insert: %d triangles, %s, size AP %.1f x SI %.1f x ML %.1f mm, y %.1f..%.1f",
              f.insert_triangles, f.insert_closed ? "closed" : "open", is_mm.x(), is_mm.y(),
              is_mm.z(), f.insert_min_mm.y(), f.insert_max_mm.y());
  if (f.insert_closed) std::printf(", volume %.0f mm^3", f.insert_volume_mm3);
  std::printf("\n");
  std::printf("articular surface: %d faces, %.0f mm^2 (medial z < 0: %.0f mm^2, %.0f %%; "
              "lateral: %.0f mm^2, %.0f %%)\n",
              f.articular_elements, f.articular_area_mm2, f.medial_area_mm2,
              100.0 * f.medial_area_mm2 / f.articular_area_mm2, f.lateral_area_mm2,
              100.0 * f.lateral_area_mm2 / f.articular_area_mm2);
  std::printf("flexion axis: along z through femur_origin_mm = [%.1f, %.1f, %.1f]%s\n",
              config.femur_origin_mm[0], config.femur_origin_mm[1], config.femur_origin_mm[2],
              mesh ? "" : " (generic: the distal arc centre)");
  for (int s = 0; s < 2; ++s) {
    const models::CondyleArc& arc = f.arcs[s];
    if (!arc.found) {
      std::printf("  %s condyle: too few points for a distal arc fit (%d)\n",
                  s == 0 ? "medial " : "lateral", arc.points);
      continue;
    }
    std::printf("  %s condyle distal arc: radius %.1f mm, centre x %.1f, y %.1f mm about the "
                "axis (slice z = %.1f mm, %d points, RMS %.2f mm)\n",
                s == 0 ? "medial " : "lateral", arc.radius_mm, arc.x_mm, arc.y_mm, arc.z_mm,
                arc.points, arc.rms_mm);
  }
  if (mesh && f.arcs[0].found && f.arcs[1].found) {
    std::printf("  arcs' centre: femur_origin_mm = [%.1f, %.1f, %.1f]%s\n",
                f.suggested_origin_mm.x(), f.suggested_origin_mm.y(), f.suggested_origin_mm.z(),
                f.flange_x_mm < 0.0 ? " in the frame turned 180 deg about y (see the warning)"
                                    : " in the rotated mesh frame");
  }
  std::printf("gap femur-insert: as placed in the files %.2f mm (negative: overlap; the run does "
              "not use it); at the run's start medial %.2f mm, lateral %.2f mm (the femur "
              "starts 1 mm above the insert's highest articular point and is lowered under the "
              "first axial load)\n",
              f.files_gap_mm, f.start_gap_medial_mm, f.start_gap_lateral_mm);
  for (const std::string& w : f.warnings) std::printf("warning: %s\n", w.c_str());
  if (f.warnings.empty()) std::printf("no warnings\n");

  // the facts as JSON, and the meshes as the run starts for the views
  const fs::path out = a.out;
  nlohmann::json j;
  j["implant"] = config.implant_kind;
  if (mesh) {
    for (const auto& [role, file] : {std::pair<std::string, std::string>{"femur", config.femur_mesh},
                                     {"insert", config.insert_mesh}}) {
      const fs::path p = models::resolve_path(config, file);
      j["meshes"][role] = {{"file", p.string()}, {"sha256", report::sha256_file(p)}};
    }
    j["units"] = config.mesh_units;
    j["rotation_deg"] = config.mesh_rotation_deg;
    j["femur_origin_mm"] = config.femur_origin_mm;
    j["insert_base_y_mm"] = config.insert_base_y_mm;
    j["left_knee"] = config.mesh_left_knee;
  }
  j["femur_box_mm"] = {to_json(f.femur_min_mm), to_json(f.femur_max_mm)};
  j["insert_box_mm"] = {to_json(f.insert_min_mm), to_json(f.insert_max_mm)};
  j["insert_closed"] = f.insert_closed;
  j["insert_volume_mm3"] = f.insert_volume_mm3;
  j["articular_elements"] = f.articular_elements;
  j["articular_area_mm2"] = f.articular_area_mm2;
  j["medial_area_mm2"] = f.medial_area_mm2;
  j["lateral_area_mm2"] = f.lateral_area_mm2;
  for (int s = 0; s < 2; ++s) {
    const models::CondyleArc& arc = f.arcs[s];
    j[s == 0 ? "medial_arc" : "lateral_arc"] = {
        {"found", arc.found}, {"radius_mm", arc.radius_mm}, {"x_mm", arc.x_mm},
        {"y_mm", arc.y_mm}, {"z_mm", arc.z_mm}, {"rms_mm", arc.rms_mm}, {"points", arc.points}};
  }
  j["arc_centre_origin_mm"] = to_json(f.suggested_origin_mm);
  auto finite_or_null = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  j["files_gap_mm"] = finite_or_null(f.files_gap_mm);
  j["start_gap_medial_mm"] = finite_or_null(f.start_gap_medial_mm);
  j["start_gap_lateral_mm"] = finite_or_null(f.start_gap_lateral_mm);
  j["warnings"] = f.warnings;
  io::write_json(out / "implant_check.json", j);

  if (!a.no_plots) {
    // the femur as the run starts: 1 mm above the insert's highest articular point
    models::TriMesh femur = implant.femur;
    const double lift = f.articular_max_mm.y() * 1e-3 - models::bounding_box(femur).min().y() + 1e-3;
    for (auto& v : femur.vertices) v.y() += lift;
    models::save_mesh(out / "implant_femur_start.stl", femur);
    models::save_mesh(out / "implant_insert.stl", implant.insert);
    const std::string title = mesh ? models::resolve_path(config, config.femur_mesh).filename().string() +
                                         " over " +
                                         models::resolve_path(config, config.insert_mesh).filename().string()
                                   : std::string("built-in generic TKR");
    char axis[64];
    std::snprintf(axis, sizeof axis, "%.6f", lift * 1e3);
    io::run_plot("implant_views.py", {(out / "implant_views.png").string(), title,
                                      (out / "implant_femur_start.stl").string(),
                                      (out / "implant_insert.stl").string(), axis});
    std::error_code ec;
    fs::remove(out / "implant_femur_start.stl", ec);
    fs::remove(out / "implant_insert.stl", ec);
  }
  std::printf("results in %s (implant_check.json%s)\n", out.string().c_str(),
              a.no_plots ? "" : ", implant_views.png");
}

}  // namespace

void add_implant_command(CLI::App& app) {
  CLI::App* implant = app.add_subcommand(
      "implant", "Check one's own implant meshes before running them (kneesim implant check).");
  implant->require_subcommand(1);
  auto args = std::make_shared<ImplantArgs>();
  CLI::App* cmd = implant->add_subcommand(
      "check",
      "Load the implant of CONFIG as a run does and refuse (exit 2, one sentence) what the rig "
      "cannot use: the same mesh twice, an inside-out or open insert, an upside-down insert or "
      "femur, a femur not over the insert, a flexion axis outside the femur, a unit mismatch. "
      "Otherwise print units, sizes, the insert's articular area and medial/lateral split, the "
      "flexion axis against the fitted distal condylar arcs, the gaps between the components, "
      "warnings about the frame (AP reversed, axis off the arcs' centre, base plane), and write "
      "DIR/implant_check.json and DIR/implant_views.png (front, side and top views of the "
      "femur over the insert as the run starts, with the axes).");
  cmd->add_option("config", args->config, "TOML config file (the built-in implant without)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_option("--set", args->sets, "override a config key (repeatable; TOML value syntax)");
  cmd->add_flag("--no-plots", args->no_plots, "skip DIR/implant_views.png");
  cmd->callback([args] { check(*args); });
}

}  // namespace kneesim::cli
