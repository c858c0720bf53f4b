#include "analysis/run/wear_job.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <thread>
#include <cstdio>
#include <numbers>
#include <optional>

#include "analysis/run/run_outputs.h"
#include "analysis/run/solid_outputs.h"
#include "engine/errors.h"
#include "engine/io/atomic_file.h"
#include "engine/io/json_out.h"
#include "engine/io/interrupt.h"
#include "engine/io/output_folder.h"
#include "engine/io/plot.h"
#include "analysis/report/wear_report.h"
#include "engine/io/progress.h"
#include "engine/io/table.h"
#include "engine/io/vtp.h"
#include "models/build_model.h"
#include "wear/archard.h"
#include "wear/checkpoint.h"
#include "wear/geometry_update.h"
#include "wear/wear_law.h"
#include "wear/wear_loop.h"
#include "wear/worn_insert.h"

namespace kneesim::run {
namespace {

constexpr double kM3ToMm3 = 1e9;

// the deformable insert's extra columns: von Mises and plastic strain, surface and subsurface
io::Table make_wear_table(const std::vector<wear::UpdateRecord>& records, double density,
                          bool solid, const WearPotentialUnit& unit) {
  io::Table t;
  t.columns = {"cycles",           "volume_mm3",        "volume_depth_mm3",
               "mass_mg",          "max_depth_mm",      "medial_volume_mm3",
               "lateral_volume_mm3", "contact_area_mm2", "peak_pressure_MPa",
               "mean_peak_pressure_MPa", "ap_rom_mm",   "ie_rom_deg",
               "refinements", "stance_mean_pressure_MPa", "wear_potential_" + unit.suffix,
               "sliding_distance_mm", "cross_shear_ratio", "max_creep_depth_mm",
               "max_penetration_mm"};
  if (solid) {
    for (const char* c : {"von_mises_max_surface_MPa", "von_mises_max_subsurface_MPa",
                          "plastic_strain_max_surface", "plastic_strain_max_subsurface"}) {
      t.columns.push_back(c);
    }
  }
  for (const auto& r : records) {
    std::vector<double> row = {
        r.cycles, r.volume * kM3ToMm3, r.volume_depth * kM3ToMm3,
        r.volume * kM3ToMm3 * density, r.max_depth * 1e3, r.medial_volume * kM3ToMm3,
        r.lateral_volume * kM3ToMm3, r.contact_area * 1e6, r.peak_pressure * 1e-6,
        r.mean_peak_pressure * 1e-6, r.ap_rom * 1e3, r.ie_rom * 180.0 / std::numbers::pi,
        r.refinements, r.stance_mean_pressure * 1e-6, r.wear_potential * unit.per_si,
        r.sliding_distance * 1e3, r.cross_shear, r.max_creep_depth * 1e3,
        r.max_penetration * 1e3};
    if (solid) {
      row.insert(row.end(), {r.von_mises_surface * 1e-6, r.von_mises_subsurface * 1e-6,
                             r.plastic_strain_surface, r.plastic_strain_subsurface});
    }
    t.add_row(row);
  }
  return t;
}

// the depth map over the insert's wear sites on the pristine geometry: the articular surface
// (rigid) or the top quads of the hex mesh, split into triangles (deformable; the points are
// all hex nodes, depth 0 off the top)
io::VtpSurface make_depth_map(const engine::Model& m, const std::vector<double>& depth) {
  io::VtpSurface v;
  io::VtpArray d{"wear_depth_mm", {}};
  if (m.insert_solid.empty()) {
    for (const auto& p : m.insert.vertices_T) v.points_mm.push_back(p * 1e3);
    v.triangles = m.insert.triangles;
    for (double x : depth) d.values.push_back(x * 1e3);
  } else {
    for (const auto& p : m.insert_solid.reference_positions) v.points_mm.push_back(p * 1e3);
    for (const auto& q : m.insert_top_faces) {
      v.triangles.emplace_back(q[0], q[1], q[2]);
      v.triangles.emplace_back(q[0], q[2], q[3]);
    }
    d.values.assign(m.insert_solid.num_nodes(), 0.0);
    for (int i = 0; i < m.insert_contact.size(); ++i) {
      d.values[m.insert_contact.nodes[i]] = depth[i] * 1e3;
    }
  }
  v.point_data.push_back(std::move(d));
  return v;
}

void write_depth_map(const std::filesystem::path& path, const engine::Model& m,
                     const std::vector<double>& depth) {
  io::write_vtp(path, make_depth_map(m, depth));
}

// least-squares slope of volume against cycles through the updates after the first [mm3/Mc]
double wear_rate(const std::vector<wear::UpdateRecord>& records) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const auto& r : records) {
    if (r.cycles <= 0) continue;
    const double x = r.cycles * 1e-6, y = r.volume * kM3ToMm3;
    sx += x, sy += y, sxx += x * x, sxy += x * y;
    ++n;
  }
  if (n == 0) return 0.0;
  if (n == 1) return sy / sx;
  // through the origin when only few points: slope = sum xy / sum xx
  return n < 3 ? sxy / sxx : (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace

bool clear_wear_outputs(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  bool any = false;
  if (!fs::is_directory(dir)) return any;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == "wear.csv" || name == "summary.json" || name == "wear.png" ||
        name == "depth_map.png" || name == "final_depth.csv" || name == "wear.checkpoint" ||
        name == "report.html" ||
        name == "summary.failed.json" || name == "wear.partial.csv" ||
        name == "kinematics.csv" || name == "insert_stress.vtu" || name == "wear_surface.vtp" ||
        name.rfind("wear_depth_", 0) == 0) {
      fs::remove(e.path());
      any = true;
    }
  }
  return any;
}

// geometry updates of the job: the intervals of --update-every or --schedule (its last entry
// repeated) summed until they reach the cycles, counted up to `limit` + 1
static long count_updates(const WearJob& j, long limit) {
  long updates = 0;
  for (long done = 0; done < j.cycles && updates <= limit; ++updates) {
    done += j.schedule.empty()
                ? j.update_every
                : j.schedule[std::min(static_cast<size_t>(updates), j.schedule.size() - 1)];
  }
  return updates;
}

// the depth maps (one .vtp per update and the pristine one) against the free space of the
// output folder: refused with the estimate when they cannot fit, a note above 2 GB. One map's
// size is that of its text with a depth of nine significant digits at every vertex (a worn
// insert's; the pristine map's zeros are shorter), formatted once.
static void check_output_size(const WearJob& j, const models::BuiltModel& built) {
  if (!j.depth_maps) return;
  const std::vector<double> typical(wear::calc_site_areas(built).size(), 1.23456789e-4);  // [m]
  const double per_map =
      static_cast<double>(io::format_vtp(make_depth_map(built.model, typical)).size());
  const long maps = count_updates(j, std::numeric_limits<long>::max() - 1) + 1;
  const double total = per_map * static_cast<double>(maps);
  const std::string what = std::to_string(maps) + " depth maps (wear_depth_<cycles>.vtp) of about " +
                           io::format_bytes(per_map) + ", about " + io::format_bytes(total) +
                           " in all";
  const double free = static_cast<double>(io::free_bytes(j.out));
  if (total > free) {
    throw InputError("--out '" + j.out.string() + "': the run would write " + what + ", more "
                     "than the " + io::format_bytes(free) + " free there; raise --update-every "
                     "(fewer updates) or pass --no-depth-maps.");
  }
  if (total > 2e9) {
    std::fprintf(stderr, "note: the run writes %s into %s (--no-depth-maps skips them)\n",
                 what.c_str(), j.out.string().c_str());
  }
}

void check_wear_job(const WearJob& j) {
  constexpr long kMaxUpdates = 10000;
  const models::MaterialConfig& m = j.config.material;
  const wear::WearLawParams law =
      wear::make_wear_law(j.config.wear, m, m.friction);  // refuses a law the material lacks
  if (j.cycles <= 0) {
    throw InputError("--cycles = " + std::to_string(j.cycles) + " is not allowed (a positive "
                     "number of gait cycles)");
  }
  if (j.schedule.empty()) {
    if (j.update_every <= 0) {
      throw InputError(j.interval_flag + " = " + std::to_string(j.update_every) +
                       " is not allowed (a positive number of cycles per geometry update)");
    }
    if (j.update_every > j.cycles) {
      throw InputError(j.interval_flag + " = " + std::to_string(j.update_every) +
                       " is larger than the run (--cycles = " + std::to_string(j.cycles) +
                       "); allowed: 1 to " + std::to_string(j.cycles));
    }
  }
  for (long s : j.schedule) {
    if (s <= 0 || s > j.cycles) {
      throw InputError("--schedule entry " + std::to_string(s) + " is not allowed (each "
                       "interval must be 1 to --cycles = " + std::to_string(j.cycles) + ")");
    }
  }
  // every update simulates a gait cycle and writes a depth map: refuse a run of millions of
  // them (--update-every 1 at 5 Mc would write about a terabyte) before it starts
  const long updates = count_updates(j, kMaxUpdates);
  if (updates > kMaxUpdates) {
    throw InputError("--cycles = " + std::to_string(j.cycles) + " with " +
                     (j.schedule.empty() ? j.interval_flag + " = " + std::to_string(j.update_every)
                                         : std::string("this --schedule")) +
                     " needs more than " + std::to_string(kMaxUpdates) +
                     " geometry updates (each simulates a gait cycle and writes a depth map); "
                     "allowed: at most " + std::to_string(kMaxUpdates) + ", e.g. " +
                     (j.schedule.empty() ? j.interval_flag : std::string("--update-every")) + " " +
                     std::to_string((j.cycles + kMaxUpdates - 1) / kMaxUpdates) + " or more");
  }
  const double k = j.config.material.wear_factor_mm3_per_Nmm;
  if (law.law != wear::WearLaw::kContactArea && !j.allow_any_wear_factor &&
      (k < 1e-12 || k > 1e-6)) {
    throw InputError("material '" + j.config.material.name + "' wear_factor_mm3_per_Nmm = " +
                     std::to_string(k) + " is outside the plausible range 1e-12 to 1e-6 "
                     "mm^3/(N mm); pass --allow-any-wear-factor to use it anyway");
  }
}

wear::WearOptions make_wear_options(const WearJob& j, const models::BuiltModel& built) {
  wear::WearOptions o;
  o.total_cycles = j.cycles;
  o.update_every = j.update_every;
  o.schedule = j.schedule;
  o.law = wear::make_wear_law(j.config.wear, built);
  return o;
}

namespace {
// the summary.json of a finished run in `dir` whose run_identity is `identity_hex`; none for
// another run's, a failed or an unreadable one (parsed without exceptions: discarded)
std::optional<nlohmann::json> read_finished_summary(const std::filesystem::path& dir,
                                                    const char* identity_hex) {
  if (!std::filesystem::exists(dir / "summary.json")) return std::nullopt;
  nlohmann::json s = nlohmann::json::parse(io::read_file(dir / "summary.json"), nullptr, false);
  if (!s.is_object() || s.value("status", "") != "complete" ||
      s.value("run_identity", "") != identity_hex) {
    return std::nullopt;
  }
  return s;
}
}  // namespace

nlohmann::json run_wear_job(const WearJob& j) {
  namespace fs = std::filesystem;
  check_wear_job(j);
  const auto t0 = std::chrono::steady_clock::now();
  bool resume = j.resume;
  const uint64_t identity = wear::fnv1a(j.identity_text.data(), j.identity_text.size());
  char identity_hex[17];
  std::snprintf(identity_hex, sizeof identity_hex, "%016llx",
                static_cast<unsigned long long>(identity));
  if (resume && !fs::exists(j.out / "wear.checkpoint")) {
    // the checkpoint goes when a run completes: this run may have finished before the
    // interruption, or been killed before its first update (then it starts afresh)
    if (std::optional<nlohmann::json> done = read_finished_summary(j.out, identity_hex)) {
      if (!j.quiet) std::fprintf(stderr, "%s is complete: nothing to resume\n",
                                 j.out.string().c_str());
      return *done;
    }
    if (!j.quiet) std::fprintf(stderr, "no checkpoint in %s yet: starting from cycle 0\n",
                               j.out.string().c_str());
    resume = false;
  }
  io::check_output_folder(j.out);  // before the model is built and the loop starts
  if (!resume) clear_wear_outputs(j.out);
  const models::BuiltModel built = models::build_model(j.config);
  check_output_size(j, built);  // still before the first cycle
  if (j.on_built) j.on_built(built);
  const bool solid = !built.model.insert_solid.empty();
  const models::MaterialConfig& mat = built.material;
  const double density_mg_per_mm3 = mat.density_g_per_cm3;  // g/cm^3 == mg/mm^3

  wear::WearOptions o = make_wear_options(j, built);
  o.checkpoint = j.out / "wear.checkpoint";
  o.resume = resume;
  o.identity = identity;
  io::ProgressBar bar("wear " + mat.name);
  if (!j.quiet) o.progress = [&bar](double f) { bar.update(f); };
  report::WearSceneRecorder scene;  // the report's depth per update
  const bool want_scene = j.report || j.scene_out;
  o.on_update = [&](const std::vector<wear::UpdateRecord>& records,
                    const std::vector<double>& depth) {
    if (want_scene) scene.add(records.back().cycles, depth);
    io::write_csv(j.out / "wear.csv", make_wear_table(records, density_mg_per_mm3, solid,
                                                        wear_potential_unit(j.config.wear.law)));
    if (j.depth_maps) {
      char name[64];
      std::snprintf(name, sizeof name, "wear_depth_%09.0f.vtp", records.back().cycles);
      write_depth_map(j.out / name, built.model, depth);
    }
  };
  // wear.csv grows with each update: until the summary it is a partial table, and an
  // interrupted or failed command leaves it as wear.partial.csv (engine/io/interrupt.h)
  const int partial_slot = io::register_partial(j.out / "wear.csv", j.out / "wear.partial.csv");
  wear::WearResult result;
  try {
    result = wear::run_wear(built, o);
  } catch (...) {
    // e.g. a full disk while an update's table or map was written
    io::unregister_partial(partial_slot);
    std::error_code ec;
    if (fs::exists(j.out / "wear.csv", ec)) {
      fs::rename(j.out / "wear.csv", j.out / "wear.partial.csv", ec);
    }
    throw;
  }
  bar.finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  nlohmann::json summary = describe_model(built, j.config);
  summary["run_identity"] = identity_hex;  // what --resume matches a finished run against
  summary["cycles"] = j.cycles;
  summary["update_every"] = j.update_every;
  summary["updates"] = static_cast<int>(result.records.size()) - 1;
  summary["seconds"] = seconds;
  summary["wear_factor_mm3_per_Nmm"] = mat.wear_factor_mm3_per_Nmm;
  summary["wear_factor_source"] = mat.wear_factor_source;
  summary["wear_factor_independent"] = mat.wear_factor_independent;
  summary.update(describe_wear_law(j.config));
  summary["density_g_per_cm3"] = mat.density_g_per_cm3;
  summary["sarkar_factor"] = wear::sarkar_factor(built.model.contact.friction);
  if (result.resumed_from_update >= 0) summary["resumed_after_update"] = result.resumed_from_update;
  if (result.status != engine::StepStatus::kOk) {
    summary["status"] = "failed";
    summary["failure"] = result.message;
    io::write_json(j.out / "summary.failed.json", summary);
    // what was complete stays under a name that cannot pass for a finished run's table
    io::unregister_partial(partial_slot);
    std::string kept = "no geometry update was completed";
    if (fs::exists(j.out / "wear.csv")) {
      fs::rename(j.out / "wear.csv", j.out / "wear.partial.csv");
      kept = "the updates completed so far are in " + (j.out / "wear.partial.csv").string();
    }
    throw std::runtime_error("the wear simulation stopped: " + result.message + "; " + kept);
  }
  const wear::UpdateRecord& last = result.records.back();
  const wear::UpdateRecord& first = result.records.front();
  summary["wear_rate_mm3_per_Mc"] = wear_rate(result.records);
  summary["volume_mm3"] = last.volume * kM3ToMm3;
  summary["volume_depth_mm3"] = last.volume_depth * kM3ToMm3;
  summary["volume_bookkeeping_rel_diff"] =
      last.volume_depth > 0 ? (last.volume - last.volume_depth) / last.volume_depth : 0.0;
  summary["mass_mg"] = last.volume * kM3ToMm3 * density_mg_per_mm3;
  summary["max_depth_mm"] = last.max_depth * 1e3;
  // penetration as a CMM or radiograph measures it: wear and creep (wear.creep) together
  summary["max_creep_depth_mm"] = last.max_creep_depth * 1e3;
  summary["max_penetration_mm"] = last.max_penetration * 1e3;
  summary["medial_volume_mm3"] = last.medial_volume * kM3ToMm3;
  summary["lateral_volume_mm3"] = last.lateral_volume * kM3ToMm3;
  summary["mean_peak_pressure_MPa"] = first.mean_peak_pressure * 1e-6;
  summary["contact_area_mm2"] = first.contact_area * 1e6;
  summary["peak_pressure_MPa"] = first.peak_pressure * 1e-6;
  // what does not depend on the wear factor: the pristine cycle's, and the potential of the
  // whole run (k x wear_potential_run_Nmm = volume_depth_mm3; wear/wear_loop.h)
  summary["stance_mean_pressure_MPa"] = first.stance_mean_pressure * 1e-6;
  summary["sliding_distance_mm"] = first.sliding_distance * 1e3;
  summary["cross_shear_ratio"] = first.cross_shear;
  const WearPotentialUnit unit = wear_potential_unit(j.config.wear.law);
  summary["wear_potential_" + unit.suffix] = first.wear_potential * unit.per_si;
  summary["wear_potential_run_" + unit.suffix] =
      wear::calc_run_wear_potential(result.records, o.law) * unit.per_si;
  summary["ap_rom_mm"] = first.ap_rom * 1e3;
  summary["ie_rom_deg"] = first.ie_rom * 180.0 / std::numbers::pi;
  summary["final_ap_rom_mm"] = last.ap_rom * 1e3;
  summary["final_ie_rom_deg"] = last.ie_rom * 180.0 / std::numbers::pi;
  // deprecated aliases under the first release's misnamed keys (degrees, not mm); written in
  // this release only, for scripts that read them (docs/user-guide.md)
  summary["ie_rom_mm"] = summary["ie_rom_deg"];
  summary["final_ie_rom_mm"] = summary["final_ie_rom_deg"];
  if (solid) {
    // the pristine cycle's maxima (as the pressures above) and the final geometry's
    summary.update(describe_solid_model(built.model));
    summary["von_mises_max_surface_MPa"] = first.von_mises_surface * 1e-6;
    summary["von_mises_max_subsurface_MPa"] = first.von_mises_subsurface * 1e-6;
    summary["plastic_strain_max_surface"] = first.plastic_strain_surface;
    summary["plastic_strain_max_subsurface"] = first.plastic_strain_subsurface;
    summary["final_von_mises_max_surface_MPa"] = last.von_mises_surface * 1e-6;
    summary["final_von_mises_max_subsurface_MPa"] = last.von_mises_subsurface * 1e-6;
    summary["final_plastic_strain_max_surface"] = last.plastic_strain_surface;
    summary["final_plastic_strain_max_subsurface"] = last.plastic_strain_subsurface;
    // quasi-static validity of the mass-scaled insert (below 5 %), as `kneesim run` reports
    // it: the pristine cycle, the final geometry's and the largest of every simulated cycle
    double worst = 0.0;
    for (const wear::UpdateRecord& r : result.records) {
      worst = std::max(worst, r.kinetic_to_internal_max);
    }
    summary["kinetic_to_internal_max"] = first.kinetic_to_internal_max;
    summary["kinetic_to_internal_cycle"] = first.kinetic_to_internal_cycle;
    summary["final_kinetic_to_internal_max"] = last.kinetic_to_internal_max;
    summary["final_kinetic_to_internal_cycle"] = last.kinetic_to_internal_cycle;
    summary["kinetic_to_internal_max_all_cycles"] = worst;
  }
  summary["status"] = "complete";

  // final depth as points for the top-view contour plot
  io::Table depth;
  depth.columns = {"x_mm", "z_mm", "depth_mm", "creep_depth_mm"};
  const std::vector<Eigen::Vector3d> sites = wear::find_site_positions(built);
  for (size_t v = 0; v < result.vertex_depth.size(); ++v) {
    const double creep = v < result.vertex_creep.size() ? result.vertex_creep[v] : 0.0;
    depth.add_row({sites[v].x() * 1e3, sites[v].z() * 1e3, result.vertex_depth[v] * 1e3,
                   creep * 1e3});
  }
  if (solid) {
    // the worn hex mesh with its element fields of the last cycle (.vtu) and its worn top
    // surface with the depth and the elements' fields under it (.vtp)
    write_solid_wear_outputs(j.out, result.final_model, result.final_state, result.von_mises_max,
                             result.vertex_depth);
  }
  io::write_csv(j.out / "final_depth.csv", depth);
  io::write_csv(j.out / "kinematics.csv", make_kinematics_table(result.frames));
  if (j.plots) {
    io::run_plot("wear.py", {(j.out / "wear.csv").string(), (j.out / "final_depth.csv").string(),
                             (j.out / "wear.png").string(), (j.out / "depth_map.png").string(),
                             mat.name});
  }
  // a resumed run may follow a failed one: no failure record stays beside the summary
  fs::remove(j.out / "summary.failed.json");
  fs::remove(j.out / "wear.partial.csv");
  io::write_json(j.out / "summary.json", summary);
  io::unregister_partial(partial_slot);  // complete (a failed write above leaves it partial)
  fs::remove(o.checkpoint);  // complete: nothing to resume
  if (want_scene) {
    // the report reads the files just written, so it shows what they say
    report::Scene3D s = scene.make_scene(built, result.frames, mat.name);
    if (j.scene_out) *j.scene_out = s;
    if (j.report) report::write_wear_report(j.out, *j.report, std::move(s));
  }
  return summary;
}

std::vector<nlohmann::json> run_wear_jobs(
    const std::vector<WearJob>& jobs, int workers,
    const std::function<void(size_t, const nlohmann::json&)>& done) {
  std::vector<nlohmann::json> results(jobs.size());
  std::vector<std::exception_ptr> errors(jobs.size());
  if (workers <= 0) workers = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::atomic<size_t> next{0};
  std::vector<std::thread> pool;
  for (int w = 0; w < workers; ++w) {
    pool.emplace_back([&] {
      for (size_t i = next++; i < jobs.size(); i = next++) {
        try {
          results[i] = run_wear_job(jobs[i]);
          if (done) done(i, results[i]);
        } catch (...) {
          errors[i] = std::current_exception();
        }
      }
    });
  }
  for (auto& t : pool) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  return results;
}

}  // namespace kneesim::run
