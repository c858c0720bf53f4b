#include "wear/wear_loop.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>

#include "engine/errors.h"
#include "engine/io/atomic_file.h"
#include "engine/solid/energy_ratio.h"
#include "wear/checkpoint.h"
#include "wear/geometry_update.h"
#include "wear/worn_insert.h"

namespace kneesim::wear {
namespace {

// stance phase of the gait cycle: heel strike to toe off, 0-60 % (ISO 14243)
constexpr double kStanceEndPct = 60.0;

// kinematic and contact figures of a simulated cycle into the record
void fill_cycle_figures(const std::vector<engine::Frame>& frames, UpdateRecord& r) {
  double ap_lo = 1e9, ap_hi = -1e9, ie_lo = 1e9, ie_hi = -1e9, area = 0.0, peaks = 0.0;
  double stance = 0.0;
  int n = 0, n_stance = 0;
  for (const engine::Frame& f : frames) {
    ap_lo = std::min(ap_lo, f.joint.ap);
    ap_hi = std::max(ap_hi, f.joint.ap);
    ie_lo = std::min(ie_lo, f.joint.ie);
    ie_hi = std::max(ie_hi, f.joint.ie);
    r.peak_pressure = std::max(r.peak_pressure, f.contact.peak_pressure);
    if (f.contact.elements_in_contact > 0) {
      area += f.contact.area[0] + f.contact.area[1];
      peaks += f.contact.peak_pressure;
      ++n;
      if (f.gait_pct < kStanceEndPct) {
        stance += f.contact.mean_pressure;
        ++n_stance;
      }
    }
  }
  r.stance_mean_pressure = n_stance ? stance / n_stance : 0.0;
  r.ap_rom = frames.empty() ? 0.0 : ap_hi - ap_lo;
  r.ie_rom = frames.empty() ? 0.0 : ie_hi - ie_lo;
  r.contact_area = n ? area / n : 0.0;
  r.mean_peak_pressure = n ? peaks / n : 0.0;
}

// volumes and depths of the cumulative depth field (per wear site, pristine tributary areas)
// against the unworn geometry
void fill_wear_figures(const std::vector<Eigen::Vector3d>& sites, const std::vector<double>& area,
                       const std::vector<double>& depth, double volume0, double volume,
                       UpdateRecord& r) {
  r.volume_depth = r.medial_volume = r.lateral_volume = r.max_depth = 0.0;
  for (size_t v = 0; v < depth.size(); ++v) {
    const double dv = depth[v] * area[v];
    r.volume_depth += dv;
    (sites[v].z() < 0.0 ? r.medial_volume : r.lateral_volume) += dv;
    r.max_depth = std::max(r.max_depth, depth[v]);
  }
  r.volume = volume0 - volume;
}

}  // namespace

std::string check_update_record(const UpdateRecord& r, bool closed_insert) {
  const double fields[] = {r.volume,       r.volume_depth,  r.max_depth,
                           r.medial_volume, r.lateral_volume, r.contact_area,
                           r.peak_pressure, r.mean_peak_pressure, r.ap_rom, r.ie_rom,
                           r.von_mises_surface, r.von_mises_subsurface,
                           r.plastic_strain_surface, r.plastic_strain_subsurface,
                           r.kinetic_to_internal_max, r.kinetic_to_internal_cycle,
                           r.wear_potential, r.sliding_distance, r.cross_shear,
                           r.stance_mean_pressure, r.max_creep_depth, r.max_penetration};
  const char* names[] = {"volume",       "volume_depth",  "max_depth",
                         "medial_volume", "lateral_volume", "contact_area",
                         "peak_pressure", "mean_peak_pressure", "ap_rom", "ie_rom",
                         "von_mises_surface", "von_mises_subsurface",
                         "plastic_strain_surface", "plastic_strain_subsurface",
                         "kinetic_to_internal_max", "kinetic_to_internal_cycle",
                         "wear_potential", "sliding_distance", "cross_shear",
                         "stance_mean_pressure", "max_creep_depth", "max_penetration"};
  const long cycles = static_cast<long>(r.cycles);
  for (size_t i = 0; i < std::size(fields); ++i) {
    if (!std::isfinite(fields[i])) {
      return "after " + std::to_string(cycles) + " cycles the " + names[i] +
             " of the update is not a finite number";
    }
  }
  if (closed_insert && r.volume_depth > 0.0) {
    const double rel = (r.volume - r.volume_depth) / r.volume_depth;
    if (std::abs(rel) > kVolumeBookkeepingTolerance) {
      char buf[300];
      std::snprintf(buf, sizeof buf,
                    "after %ld cycles the enclosed-volume loss %.4g mm^3 and the depth integral "
                    "%.4g mm^3 differ by %.3g %% (allowed %.3g %%): the worn geometry is not "
                    "consistent with the wear depth",
                    cycles, r.volume * 1e9, r.volume_depth * 1e9, 100.0 * rel,
                    100.0 * kVolumeBookkeepingTolerance);
      return buf;
    }
  }
  return "";
}

namespace {

// the contact frequency the next cycle is given a step for, over the one the last cycle met:
// wear makes the insert more conforming and the contact stiffer between two cycles (up to
// 21 % per 250 000-cycle update for CFR-PEEK at ratio 0.85 on the stanmore rig), and a cycle
// that trips the stability monitor is retried with a step from the frequency measured in the
// failed attempt, a threshold event that makes the run's result jump with its inputs
constexpr double kStiffeningAllowance = 1.25;

// what a simulated cycle of the deformable insert leaves besides its frames: each element's
// largest von Mises stress [Pa] and the solid's kinetic and internal energy per step [J]
struct SolidCycle {
  std::vector<double> von_mises_max;
  std::vector<double> kinetic, internal;
};

// one gait cycle on the current geometry from `state` (advanced on success); wear makes the
// insert more conforming and the contact stiffer, so when the stability monitor trips the cycle
// is repeated with the step the measured frequency allows, and a cycle close to the limit
// shortens the step of the next one. `acc` (may be null) accumulates the cycle's wear depth;
// `cycle` receives the deformable insert's per-cycle figures.
engine::RunResult simulate_cycle(engine::Model& model, engine::State& state, double dt_safety,
                                 const WearLawParams& law, WearAccumulator* acc,
                                 SolidCycle& cycle) {
  engine::RunOptions ro;
  ro.cycles = 1;
  const bool solid = !model.insert_solid.empty();
  cycle.von_mises_max.assign(model.insert_solid.num_elements(), 0.0);
  const auto reserve = [&cycle, &model, solid] {
    cycle.kinetic.clear();
    cycle.internal.clear();
    if (!solid) return;
    const size_t steps = static_cast<size_t>(std::lround(model.period / model.dt)) + 2;
    cycle.kinetic.reserve(steps);
    cycle.internal.reserve(steps);
  };
  reserve();
  ro.observer = [acc, solid, &cycle](const engine::Model& m, const engine::State& s,
                                     const engine::Data& d) {
    if (acc) observe_wear(*acc, m, s, d);
    if (!solid) return;
    const engine::solid::SolidData& sd = d.insert_solid;
    const std::vector<double>& vm = sd.von_mises;
    for (size_t e = 0; e < vm.size(); ++e) {
      cycle.von_mises_max[e] = std::max(cycle.von_mises_max[e], vm[e]);
    }
    cycle.kinetic.push_back(sd.kinetic_energy);
    cycle.internal.push_back(sd.total_strain_energy + sd.total_plastic_work);
  };
  const std::function<void()> reset = [acc, &model, &law, &cycle, &reserve] {
    if (acc) *acc = make_accumulator(model, law);
    std::fill(cycle.von_mises_max.begin(), cycle.von_mises_max.end(), 0.0);
    reserve();
  };
  const engine::RunResult run = engine::simulate_with_retry(model, state, ro, dt_safety, 4, reset);
  if (run.status == engine::StepStatus::kOk) {
    model.dt = next_cycle_step(model, kStiffeningAllowance * run.omega_max, dt_safety);
  }
  return run;
}

// the deformable insert's stress and plastic-strain maxima of a cycle, surface layer (the
// elements under the top faces) and subsurface, and its energy ratios, into the record
void fill_solid_figures(const engine::Model& model, const engine::State& state,
                        const SolidCycle& cycle, UpdateRecord& r) {
  const int n = model.insert_solid.num_elements();
  std::vector<unsigned char> surface(n, 0);
  for (int e : model.insert_top_face_element) surface[e] = 1;
  r.von_mises_surface = r.von_mises_subsurface = 0.0;
  r.plastic_strain_surface = r.plastic_strain_subsurface = 0.0;
  for (int e = 0; e < n; ++e) {
    double& vm = surface[e] ? r.von_mises_surface : r.von_mises_subsurface;
    double& ep = surface[e] ? r.plastic_strain_surface : r.plastic_strain_subsurface;
    vm = std::max(vm, cycle.von_mises_max[e]);
    ep = std::max(ep, state.insert_solid.alpha[e]);
  }
  const engine::solid::EnergyRatio energy =
      engine::solid::calc_energy_ratio(cycle.kinetic, cycle.internal);
  r.kinetic_to_internal_max = energy.max;
  r.kinetic_to_internal_cycle = energy.cycle;
}

// creep penetration per site after the record's cycles, from the cycle-mean elastic
// penetration of the cycle simulated on the record's geometry (`acc`), and the record's maxima
void fill_creep_figures(const engine::Model& model, const WearAccumulator& acc,
                        const WearLawParams& law, const std::vector<double>& depth,
                        UpdateRecord& r, std::vector<double>& creep) {
  const std::vector<double> elastic = calc_site_mean_penetration(model, acc);
  creep.assign(depth.size(), 0.0);
  r.max_creep_depth = 0.0;
  r.max_penetration = 0.0;
  for (size_t v = 0; v < depth.size(); ++v) {
    creep[v] = creep_depth(law, elastic[v], r.cycles * model.period);
    r.max_creep_depth = std::max(r.max_creep_depth, creep[v]);
    r.max_penetration = std::max(r.max_penetration, depth[v] + creep[v]);
  }
}

// the last record gets the figures of a cycle simulated on its geometry (with the wear
// accumulated over it) and is complete
void complete_record(const engine::RunResult& run, const engine::Model& model,
                     const engine::State& state, const SolidCycle& cycle,
                     const WearAccumulator& acc, WearResult& result,
                     const std::vector<double>& depth, const WearOptions& o) {
  fill_cycle_figures(run.frames, result.records.back());
  result.records.back().wear_potential = acc.wear_potential();
  result.records.back().sliding_distance = acc.sliding_distance();
  result.records.back().cross_shear = acc.mean_cross_shear();
  fill_creep_figures(model, acc, o.law, depth, result.records.back(), result.vertex_creep);
  if (!model.insert_solid.empty()) {
    fill_solid_figures(model, state, cycle, result.records.back());
  }
  result.frames = run.frames;
  if (o.on_update) o.on_update(result.records, depth);
}
}  // namespace

double calc_run_wear_potential(const std::vector<UpdateRecord>& records, const WearLawParams& law) {
  double w = 0.0;
  for (size_t u = 0; u + 1 < records.size(); ++u) {
    const double n = records[u + 1].cycles - records[u].cycles;
    w += records[u].wear_potential * effective_cycles(law, records[u].cycles, n);
  }
  return w;
}

double next_cycle_step(const engine::Model& model, double omega_max, double dt_safety) {
  if (!(omega_max > 0.0)) return model.dt;
  const double limit = engine::find_step_for_frequency(model, omega_max, dt_safety);
  // a step already within the limit is kept as it is (re-rounding it to whole steps per cycle
  // could shorten it by one step per cycle)
  return limit >= model.dt ? model.dt : engine::find_whole_cycle_step(model, limit);
}

long update_interval(const WearOptions& o, int u) {
  if (o.schedule.empty()) return o.update_every;
  return o.schedule[std::min<size_t>(u, o.schedule.size() - 1)];
}

WearResult run_wear(const models::BuiltModel& pristine, const WearOptions& o) {
  WearResult result;
  engine::Model model = pristine.model;
  const std::vector<Eigen::Vector3d> sites0 = find_site_positions(pristine);
  const std::vector<double> areas0 = calc_site_areas(pristine);
  WornInsert insert = make_pristine_insert(pristine);
  const double volume0 = calc_insert_volume(pristine, insert);
  // the deformable insert's hex mesh is closed by construction
  if (o.law.creep && insert.kind == InsertKind::kDeformable) {
    throw InputError("wear.creep = true is not allowed with insert = \"deformable\" (the "
                     "solid insert deforms by its own material model); allowed: wear.creep = "
                     "false, or insert = \"rigid\"");
  }
  const bool closed_insert =
      insert.kind == InsertKind::kDeformable || pristine.implant.insert_volume > 0.0;
  std::vector<double> depth(sites0.size(), 0.0);
  engine::State state = engine::make_initial_state(model);
  SolidCycle cycle;  // the deformable insert's figures of the last simulated cycle
  long cycles_done = 0;
  int u = 0;

  if (o.resume) {
    const Checkpoint c = read_checkpoint(o.checkpoint, o.identity);
    if (c.insert_vertices.size() != insert.points.size() || c.vertex_depth.size() != depth.size() ||
        c.state.insert_solid.position.size() != state.insert_solid.position.size()) {
      throw InputError(o.checkpoint.string() + ": the checkpoint holds an insert of " +
                       std::to_string(c.insert_vertices.size()) + " vertices, the model has " +
                       std::to_string(insert.points.size()) + "; it belongs to another "
                       "implant or mesh: delete it or run without --resume");
    }
    cycles_done = c.cycles_done;
    u = c.next_update;
    state = c.state;  // a deformable insert's nodes are already on the worn reference
    insert.points = c.insert_vertices;
    depth = c.vertex_depth;
    result.records = c.records;
    result.frames = c.frames;
    result.resumed_from_update = u;
    model.dt = c.dt;  // the step the run had adapted to (wear makes the contact stiffer)
    apply_worn_insert(pristine, insert, model, nullptr);
  } else {
    // a settling cycle from rest brings the carriages into their periodic motion; its
    // kinematics are not those of a settled cycle (the AP range differs by about 5 %), so it is
    // reported nowhere: row 0 (cycle 0, the pristine insert) takes the figures of the first
    // wear cycle, which runs on the pristine insert from the settled state, as `kneesim run`
    // reports its last cycle; from rest the contact can stiffen beyond the estimated limit,
    // so it gets the step retry too
    engine::RunOptions ro;
    ro.cycles = 1;
    const engine::RunResult run =
        engine::simulate_with_retry(model, state, ro, pristine.dt_safety);
    if (run.status != engine::StepStatus::kOk) {
      result.status = run.status;
      result.message = engine::to_string(run.status);
      return result;
    }
    result.records.push_back(UpdateRecord{});
    result.frames = run.frames;
  }

  while (cycles_done < o.total_cycles) {
    // one cycle on the current geometry, accumulating the per-cycle depth
    WearAccumulator acc = make_accumulator(model, o.law);
    const engine::RunResult run =
        simulate_cycle(model, state, pristine.dt_safety, o.law, &acc, cycle);
    if (run.status != engine::StepStatus::kOk) {
      result.status = run.status;
      result.message = engine::to_string(run.status);
      break;
    }
    // the cycle's kinematics and contact describe the geometry it ran on: the last record's
    complete_record(run, model, state, cycle, acc, result, depth, o);
    const std::vector<double> per_cycle = calc_site_depth(model, acc);

    // scale by the cycles of this update; halve them while a face or element would fold
    long interval = std::min(update_interval(o, u), o.total_cycles - cycles_done);
    const std::vector<Eigen::Vector3d> normals = calc_site_normals(model);
    InsertRecession rec;
    int refinements = 0;
    for (;;) {
      std::vector<double> step_depth(per_cycle.size());
      const double n_eff = effective_cycles(o.law, static_cast<double>(cycles_done), interval);
      for (size_t v = 0; v < per_cycle.size(); ++v) step_depth[v] = per_cycle[v] * n_eff;
      rec = recede_insert(pristine, insert, normals, step_depth);
      if (rec.folds == 0 || interval <= 1) break;
      interval = std::max(1L, interval / 2);
      ++refinements;
    }
    // an insert worn down to a tenth of its height has worn through: the contact model (and
    // the insert) no longer hold, and no interval refinement changes the outcome
    if (const int v = find_worn_through_site(pristine, rec.insert); v >= 0) {
      result.status = engine::StepStatus::kRunawayPenetration;
      result.message = "the insert wore through after about " +
                       std::to_string(cycles_done + interval) + " cycles (" +
                       (insert.kind == InsertKind::kRigid ? "articular vertex " : "top node ") +
                       std::to_string(v) + " is within 10 % of its height from the base)";
      break;
    }
    if (rec.folds > 0) {
      result.status = engine::StepStatus::kRunawayPenetration;
      result.message = "after " + std::to_string(cycles_done) + " cycles a single wear cycle "
                       "would fold " + std::to_string(rec.folds) + " " + fold_name(insert.kind) +
                       " (reversed or collapsed against the pristine insert: the wear scar has "
                       "reached parts that do not recede with it, e.g. the side walls)";
      break;
    }
    const double n_eff = effective_cycles(o.law, static_cast<double>(cycles_done), interval);
    for (size_t v = 0; v < depth.size(); ++v) depth[v] += per_cycle[v] * n_eff;
    insert = std::move(rec.insert);
    apply_worn_insert(pristine, insert, model, &state);
    cycles_done += interval;
    ++u;

    // the new geometry's record; its kinematic and contact figures come from the next cycle
    UpdateRecord r;
    r.cycles = static_cast<double>(cycles_done);
    r.refinements = refinements;
    fill_wear_figures(sites0, areas0, depth, volume0, calc_insert_volume(pristine, insert), r);
    // a result with NaN or inconsistent volumes never passes for a finished run
    if (std::string why = check_update_record(r, closed_insert); !why.empty()) {
      result.status = engine::StepStatus::kNotFinite;
      result.message = why;
      break;
    }
    result.records.push_back(r);
    if (o.on_insert && insert.kind == InsertKind::kRigid) {
      o.on_insert(make_worn_mesh(pristine, insert));
    }
    if (!o.checkpoint.empty()) {
      Checkpoint c;
      c.identity = o.identity;
      c.cycles_done = cycles_done;
      c.next_update = u;
      c.state = state;
      c.insert_vertices = insert.points;
      c.vertex_depth = depth;
      c.records = result.records;
      c.dt = model.dt;
      c.frames = result.frames;
      write_checkpoint(o.checkpoint, c);
    }
    if (o.progress) o.progress(static_cast<double>(cycles_done) / o.total_cycles);
  }
  // the last geometry's kinematics and contact: one more cycle on it, its wear accumulated for
  // the record's factor-free figures only
  if (result.status == engine::StepStatus::kOk) {
    // its accumulator gives the final geometry's elastic penetration (creep); its wear is not
    // applied
    WearAccumulator acc = make_accumulator(model, o.law);
    const engine::RunResult run =
        simulate_cycle(model, state, pristine.dt_safety, o.law, &acc, cycle);
    if (run.status != engine::StepStatus::kOk) {
      result.status = run.status;
      result.message = std::string(engine::to_string(run.status)) + " in the cycle on the final geometry";
    } else {
      complete_record(run, model, state, cycle, acc, result, depth, o);
    }
  }
  result.vertex_depth = depth;
  if (insert.kind == InsertKind::kRigid) result.worn = make_worn_mesh(pristine, insert);
  result.worn_insert = std::move(insert);
  result.final_model = std::move(model);
  result.final_state = std::move(state);
  result.von_mises_max = std::move(cycle.von_mises_max);
  return result;
}

}  // namespace kneesim::wear
