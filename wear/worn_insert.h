// The geometry the wear loop recedes, for either insert (issue 11 item 4): one interface over
// the rigid insert's closed triangle mesh and the deformable insert's hex mesh, so that
// wear/wear_loop.cpp runs one schedule, one accumulation and one bookkeeping for both.
//
//   rigid       sites = the articular vertices; points = the insert mesh's vertices; the
//               Archard depth is accumulated per articular element and spread to the vertices
//               (wear/geometry_update.h); volume = the enclosed volume of the closed mesh;
//               a fold = a face reversed or collapsed; the next Model gets the worn surface.
//   deformable  sites = the top-surface contact nodes; points = the hex nodes' reference
//               positions; the depth is accumulated per node from its penalty pressure and
//               slip; the top nodes recede along the surface normal and every column is
//               re-graded (models/deformable_insert.h); volume = the hex mesh's volume; a fold
//               = an element inverted or collapsed; the next Model is the solid rebuilt on the
//               worn reference, the State carried onto it with its displacements.
//
// The depth integral sum_site depth A (pristine tributary areas) against the volume change of
// the worn geometry is the bookkeeping check of both (wear_loop.h, kVolumeBookkeepingTolerance).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "engine/state.h"
#include "models/build_model.h"
#include "wear/wear_accumulator.h"

namespace kneesim::wear {

enum class InsertKind { kRigid, kDeformable };

struct WornInsert {
  InsertKind kind = InsertKind::kRigid;
  std::vector<Eigen::Vector3d> points;  // rigid: insert mesh vertices; deformable: hex node
                                        // reference positions [m], T frame
};

InsertKind find_insert_kind(const models::BuiltModel& built);

// the pristine geometry of the built model's insert
WornInsert make_pristine_insert(const models::BuiltModel& built);

// positions of the wear sites in the pristine insert [m], T frame (medial: z < 0)
std::vector<Eigen::Vector3d> find_site_positions(const models::BuiltModel& pristine);

// pristine tributary area of each wear site [m^2]
std::vector<double> calc_site_areas(const models::BuiltModel& pristine);

// an accumulator sized for the model's insert and its observer for engine::RunOptions
WearAccumulator make_accumulator(const engine::Model& model, const WearLawParams& law);
void observe_wear(WearAccumulator& acc, const engine::Model& model, const engine::State& state,
                  const engine::Data& data);

// depth per wear site of one cycle [m] from the accumulator of that cycle on `model`
std::vector<double> calc_site_depth(const engine::Model& model, const WearAccumulator& acc);
// the sites' cycle-mean elastic penetration of the accumulator's cycle (creep's d_el) [m]
std::vector<double> calc_site_mean_penetration(const engine::Model& model,
                                               const WearAccumulator& acc);

// unit outward normals of the wear sites on the model's current geometry
std::vector<Eigen::Vector3d> calc_site_normals(const engine::Model& model);

struct InsertRecession {
  WornInsert insert;
  int folds = 0;  // faces (rigid) or elements (deformable) reversed or collapsed
};

// `current` with each site receded by depth along -normal; folds are counted against the
// geometry before this recession and against the pristine one
InsertRecession recede_insert(const models::BuiltModel& pristine, const WornInsert& current,
                              const std::vector<Eigen::Vector3d>& normal,
                              const std::vector<double>& depth);

// what a fold is, for the stop message: "insert faces" or "insert elements"
const char* fold_name(InsertKind kind);

// volume of the insert [m^3]: enclosed (rigid, closed mesh) or hex mesh (deformable)
double calc_insert_volume(const models::BuiltModel& pristine, const WornInsert& insert);

// first site whose height above the base fell below 10 % of its pristine height, or -1
int find_worn_through_site(const models::BuiltModel& pristine, const WornInsert& insert);

// the model on the worn geometry, and the deformable insert's state (if not null) carried onto
// the worn reference; the model is a pure function of (pristine, worn, model.dt), so a resumed
// run rebuilds the model it left (its checkpointed state is already on the worn reference)
void apply_worn_insert(const models::BuiltModel& pristine, const WornInsert& worn,
                       engine::Model& model, engine::State* state);

// the rigid insert's worn closed mesh (the pristine mesh with the worn vertices)
models::TriMesh make_worn_mesh(const models::BuiltModel& pristine, const WornInsert& worn);

}  // namespace kneesim::wear
