// One's own implant meshes are refused before any simulation when the rig cannot use them
// (models/implant_check.h), through load_implant, the call build_model makes. The meshes are
// the built-in generic implant's, saved as STL files and then broken one way per class: the
// reference for each case is how the file was made (a flipped winding is inside out by
// construction, a 180 deg turn about x puts the base on top, ...). The same meshes unbroken
// pass, and describe_implant finds the generic femur's distal arc radius, a design parameter.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <string>

#include "engine/errors.h"
#include "models/build_model.h"
#include "models/config.h"
#include "models/generic_tkr.h"
#include "models/implant_check.h"
#include "models/mesh_io.h"
#include "temp_dir.h"

using namespace kneesim::models;
using kneesim::InputError;
using kneesim::test::TempDir;

namespace {

struct Meshes {
  TriMesh femur, insert;
  GenericTkrParams params;
};

Meshes generic_meshes() {
  Meshes m;
  Config c;
  m.params = generic_params(c);
  m.femur = make_generic_femur(m.params, 1.5e-3);
  m.insert = make_generic_insert(m.params, 1.5e-3);
  return m;
}

Config mesh_config(const std::string& femur, const std::string& insert) {
  Config c;
  c.implant_kind = "mesh";
  c.femur_mesh = femur;
  c.insert_mesh = insert;
  c.mesh_units = "m";
  return c;
}

TriMesh moved(const TriMesh& m, const Eigen::Vector3d& d) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = d;
  return transformed(m, X);
}

// the message of the refusal, or "" when the implant loads
std::string refusal(const Config& c) {
  try {
    load_implant(c);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("the generic implant's meshes saved as files pass and are described") {
  TempDir dir;
  const Meshes g = generic_meshes();
  const auto f = dir.path / "femur.stl", i = dir.path / "insert.stl";
  save_mesh(f, g.femur);
  save_mesh(i, g.insert);
  const Config c = mesh_config(f.string(), i.string());
  CHECK(refusal(c).empty());
  const Implant imp = load_implant(c);
  const auto surface = make_insert_surface(imp.insert, 0.0, c.articular_min_normal_y, nullptr,
                                           nullptr);
  const ImplantFacts facts = describe_implant(c, imp, surface);
  // the generic femur's distal sagittal radius is a design parameter (38 mm by default); the
  // fit on a 1.5 mm mesh is within 1 mm of it, both condyles
  for (const CondyleArc& arc : facts.arcs) {
    REQUIRE(arc.found);
    CHECK(arc.radius_mm == doctest::Approx(g.params.femur_distal_radius_m * 1e3).epsilon(0.03));
  }
  // the generic implant is symmetric: the articular area splits evenly
  CHECK(facts.medial_area_mm2 == doctest::Approx(facts.lateral_area_mm2).epsilon(0.02));
  CHECK(facts.articular_area_mm2 > 0.0);
  CHECK(facts.insert_closed);
  CHECK(facts.insert_volume_mm3 > 0.0);
  // both condyles land together as the run starts: same gap on each side
  CHECK(facts.start_gap_medial_mm == doctest::Approx(facts.start_gap_lateral_mm).epsilon(0.05));
}

TEST_CASE("each class of broken implant meshes is refused naming the file and key") {
  TempDir dir;
  const Meshes g = generic_meshes();
  const auto femur = dir.path / "femur.stl", insert = dir.path / "insert.stl";
  save_mesh(femur, g.femur);
  save_mesh(insert, g.insert);
  auto write = [&](const std::string& name, const TriMesh& m) {
    save_mesh(dir.path / name, m);
    return (dir.path / name).string();
  };

  SUBCASE("inside-out insert") {
    const std::string e = refusal(mesh_config(femur.string(), write("inside_out.stl", flipped(g.insert))));
    CHECK(has(e, "inside_out.stl: implant.mesh.insert is inside out"));
    CHECK(has(e, "reverse the vertex order"));
  }
  SUBCASE("inside-out femur (a closed femur)") {
    if (check_mesh(g.femur).closed()) {
      const std::string e = refusal(mesh_config(write("f_inside_out.stl", flipped(g.femur)), insert.string()));
      CHECK(has(e, "f_inside_out.stl: implant.mesh.femur is inside out"));
    }
  }
  SUBCASE("open insert") {
    TriMesh open = g.insert;
    open.triangles.resize(open.triangles.size() - 3);
    const std::string e = refusal(mesh_config(femur.string(), write("open.stl", open)));
    CHECK(has(e, "open.stl: the mesh is not closed"));
    CHECK(has(e, "implant.mesh.insert_closed"));
  }
  SUBCASE("upside-down insert") {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()).toRotationMatrix();
    TriMesh up = transformed(g.insert, X);
    up = moved(up, Eigen::Vector3d(0, -bounding_box(up).min().y(), 0));  // base plane at y = 0
    const std::string e = refusal(mesh_config(femur.string(), write("upside.stl", up)));
    CHECK(has(e, "upside.stl: implant.mesh.insert is upside down"));
    CHECK(has(e, "implant.mesh.rotation_deg"));
  }
  SUBCASE("upside-down femur") {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const std::string e = refusal(mesh_config(write("f_upside.stl", transformed(g.femur, X)), insert.string()));
    CHECK(has(e, "f_upside.stl"));
    CHECK(!e.empty());
  }
  SUBCASE("femur 500 mm away") {
    const std::string e = refusal(mesh_config(write("far.stl", moved(g.femur, {0.5, 0, 0})), insert.string()));
    CHECK(has(e, "far.stl: the femoral component is not above the insert"));
  }
  SUBCASE("femur 100 mm up: the flexion axis outside the component") {
    const std::string e = refusal(mesh_config(write("up.stl", moved(g.femur, {0, 0.1, 0})), insert.string()));
    CHECK(has(e, "implant.mesh.femur_origin_mm = [0.0, 0.0, 0.0] puts the flexion axis outside"));
  }
  SUBCASE("femur 100 mm up with its origin there too passes") {
    Config c = mesh_config(write("up2.stl", moved(g.femur, {0, 0.1, 0})), insert.string());
    c.femur_origin_mm = {0.0, 100.0, 0.0};
    CHECK(refusal(c).empty());
  }
  SUBCASE("the same mesh twice, and the insert given as the femur") {
    CHECK(has(refusal(mesh_config(insert.string(), insert.string())), "are the same mesh"));
    const std::string copy = write("copy.stl", g.insert);
    CHECK(has(refusal(mesh_config(copy, insert.string())), "are the same mesh"));
  }
  SUBCASE("millimetres declared as metres") {
    TriMesh mm = g.femur;
    for (auto& v : mm.vertices) v *= 1000.0;
    const std::string e = refusal(mesh_config(write("mm.stl", mm), insert.string()));
    CHECK(has(e, "mm.stl"));
    CHECK(has(e, "implant.mesh.units"));
  }
}

TEST_CASE("describe_implant warns when anterior and posterior are reversed and suggests the turn") {
  TempDir dir;
  const Meshes g = generic_meshes();
  // the generic femur has no anterior flange; give it one: a block at its anterior top, the
  // highest point, as real components have
  TriMesh femur = g.femur;
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const auto box = bounding_box(femur);
  TriMesh flange;
  flange.vertices = {{0.02, box.max().y(), -0.01}, {0.03, box.max().y(), -0.01},
                     {0.025, box.max().y() + 0.02, 0.0}, {0.025, box.max().y(), 0.01}};
  flange.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  append(femur, flange);
  const TriMesh turned = transformed(femur, X);  // anterior now at -x: the files' frame
  save_mesh(dir.path / "femur.stl", turned);
  save_mesh(dir.path / "insert.stl", transformed(g.insert, X));
  Config c = mesh_config((dir.path / "femur.stl").string(), (dir.path / "insert.stl").string());
  auto describe = [&](const Config& cfg) {
    const Implant imp = load_implant(cfg);
    return describe_implant(cfg, imp, make_insert_surface(imp.insert, 0.0,
                                                          cfg.articular_min_normal_y, nullptr,
                                                          nullptr));
  };
  const ImplantFacts naive = describe(c);
  CHECK(naive.flange_x_mm < 0.0);
  REQUIRE(!naive.warnings.empty());
  CHECK(has(naive.warnings[0], "set rotation_deg = [0.0, 180.0, 0.0]"));
  c.mesh_rotation_deg = {0.0, 180.0, 0.0};
  const ImplantFacts fixed = describe(c);
  CHECK(fixed.flange_x_mm > 0.0);
  CHECK(fixed.warnings.empty());
  // an axis 5 mm off the arcs' centre is warned about, with the centre
  c.femur_origin_mm = {5.0, 0.0, 0.0};
  const ImplantFacts off = describe(c);
  REQUIRE(off.warnings.size() == 1);
  CHECK(has(off.warnings[0], "is 5.0 mm from the centre of the distal condylar arcs"));
  // the centre is a property of the mesh, the same wherever the axis is put
  CHECK(std::abs(off.suggested_origin_mm.x() - fixed.suggested_origin_mm.x()) < 0.11);
}
