#include "wear/worn_insert.h"

#include <algorithm>

#include "models/deformable_insert.h"
#include "wear/geometry_update.h"

namespace kneesim::wear {

InsertKind find_insert_kind(const models::BuiltModel& built) {
  return built.model.insert_solid.empty() ? InsertKind::kRigid : InsertKind::kDeformable;
}

WornInsert make_pristine_insert(const models::BuiltModel& built) {
  WornInsert w;
  w.kind = find_insert_kind(built);
  switch (w.kind) {
    case InsertKind::kRigid: w.points = built.implant.insert.vertices; break;
    case InsertKind::kDeformable: w.points = built.model.insert_solid.reference_positions; break;
  }
  return w;
}

std::vector<Eigen::Vector3d> find_site_positions(const models::BuiltModel& pristine) {
  switch (find_insert_kind(pristine)) {
    case InsertKind::kRigid: return pristine.model.insert.vertices_T;
    case InsertKind::kDeformable: {
      std::vector<Eigen::Vector3d> p;
      for (int n : pristine.model.insert_contact.nodes) {
        p.push_back(pristine.model.insert_solid.reference_positions[n]);
      }
      return p;
    }
  }
  return {};
}

std::vector<double> calc_site_areas(const models::BuiltModel& pristine) {
  switch (find_insert_kind(pristine)) {
    case InsertKind::kRigid: return vertex_areas(pristine.model.insert);
    case InsertKind::kDeformable: return pristine.model.insert_contact.area;
  }
  return {};
}

WearAccumulator make_accumulator(const engine::Model& model, const WearLawParams& law) {
  return WearAccumulator(model.insert_solid.empty() ? model.insert.size()
                                                    : model.insert_contact.size(),
                         law);
}

void observe_wear(WearAccumulator& acc, const engine::Model& model, const engine::State& state,
                  const engine::Data& data) {
  if (model.insert_solid.empty()) {
    acc.observe(model, state, data);
  } else {
    acc.observe_nodes(model, state, data);
  }
}

std::vector<double> calc_site_depth(const engine::Model& model, const WearAccumulator& acc) {
  if (model.insert_solid.empty()) return spread_to_vertices(model.insert, acc.depth_per_cycle());
  return acc.depth_per_cycle();
}

std::vector<double> calc_site_mean_penetration(const engine::Model& model,
                                               const WearAccumulator& acc) {
  if (model.insert_solid.empty()) return spread_to_vertices(model.insert, acc.mean_penetration());
  return acc.mean_penetration();
}

std::vector<Eigen::Vector3d> calc_site_normals(const engine::Model& model) {
  if (model.insert_solid.empty()) return articular_vertex_normals(model.insert);
  return models::calc_top_node_normals(model, model.insert_solid.reference_positions);
}

models::TriMesh make_worn_mesh(const models::BuiltModel& pristine, const WornInsert& worn) {
  models::TriMesh m = pristine.implant.insert;
  if (worn.kind == InsertKind::kRigid) m.vertices = worn.points;
  return m;
}

InsertRecession recede_insert(const models::BuiltModel& pristine, const WornInsert& current,
                              const std::vector<Eigen::Vector3d>& normal,
                              const std::vector<double>& depth) {
  InsertRecession r;
  r.insert.kind = current.kind;
  switch (current.kind) {
    case InsertKind::kRigid: {
      const models::TriMesh before = make_worn_mesh(pristine, current);
      RecessionResult rec =
          recede(before, pristine.implant.articular_vertex_to_insert, normal, depth);
      // against the pristine insert too: a face may also turn over a little per update
      r.folds = std::max(rec.inverted_faces,
                         count_inverted_faces(pristine.implant.insert, rec.insert));
      r.insert.points = std::move(rec.insert.vertices);
      break;
    }
    case InsertKind::kDeformable: {
      r.insert.points = models::recede_insert_columns(pristine.model, current.points, normal, depth);
      r.folds = models::count_collapsed_elements(pristine.model, r.insert.points);
      break;
    }
  }
  return r;
}

const char* fold_name(InsertKind kind) {
  switch (kind) {
    case InsertKind::kRigid: return "insert faces";
    case InsertKind::kDeformable: return "insert elements";
  }
  return "";
}

double calc_insert_volume(const models::BuiltModel& pristine, const WornInsert& insert) {
  switch (insert.kind) {
    case InsertKind::kRigid: return models::enclosed_volume(make_worn_mesh(pristine, insert));
    case InsertKind::kDeformable: return models::calc_hex_volume(pristine.model, insert.points);
  }
  return 0.0;
}

int find_worn_through_site(const models::BuiltModel& pristine, const WornInsert& insert) {
  switch (insert.kind) {
    case InsertKind::kRigid: {
      const auto& map = pristine.implant.articular_vertex_to_insert;
      for (size_t v = 0; v < map.size(); ++v) {
        const double h0 = pristine.implant.insert.vertices[map[v]].y();
        if (insert.points[map[v]].y() < 0.1 * h0) return static_cast<int>(v);
      }
      return -1;
    }
    case InsertKind::kDeformable: {
      // the column's base node is fixed on the base plane: heights are above it
      const auto& X0 = pristine.model.insert_solid.reference_positions;
      const auto& nodes = pristine.model.insert_contact.nodes;
      const int per_column =
          pristine.model.insert_solid.num_nodes() /
          std::max<int>(1, static_cast<int>(pristine.model.insert_base_nodes.size()));
      for (size_t i = 0; i < nodes.size(); ++i) {
        const int top = nodes[i], base = top - (per_column - 1);
        const double h0 = X0[top].y() - X0[base].y();
        if (insert.points[top].y() - insert.points[base].y() < 0.1 * h0) {
          return static_cast<int>(i);
        }
      }
      return -1;
    }
  }
  return -1;
}

void apply_worn_insert(const models::BuiltModel& pristine, const WornInsert& worn,
                       engine::Model& model, engine::State* state) {
  switch (worn.kind) {
    case InsertKind::kRigid:
      model.insert = models::make_worn_insert_surface(pristine, make_worn_mesh(pristine, worn));
      break;
    case InsertKind::kDeformable:
      models::apply_worn_deformable_insert(pristine.model, pristine.dt_safety, worn.points, model,
                                           state);
      break;
  }
}

}  // namespace kneesim::wear
