// One wear simulation with all its outputs (wear.csv, summary.json, depth maps, plots,
// checkpoint) as a library call: `kneesim wear`, each material of `kneesim compare` and each
// interval of the convergence study run through it.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/report/provenance.h"
#include "analysis/report/scene3d.h"
#include "models/build_model.h"
#include "models/config.h"
#include "wear/wear_loop.h"

namespace kneesim::run {

struct WearJob {
  models::Config config;
  std::string identity_text;      // what defines the run (for the checkpoint identity)
  long cycles = 5'000'000;
  long update_every = 250'000;
  std::vector<long> schedule;     // overrides update_every when not empty
  // the option that set update_every, named in messages ("--update-every", "--convergence")
  std::string interval_flag = "--update-every";
  std::filesystem::path out;
  bool resume = false;
  bool allow_any_wear_factor = false;
  bool quiet = false;
  bool plots = true;
  bool depth_maps = true;         // a .vtp per update
  // writes out/report.html (analysis/report/wear_report.h) with this provenance when set
  std::optional<report::Provenance> report;
  // receives the report's 3D scene (wear depth per update) when set (compare's report)
  report::Scene3D* scene_out = nullptr;
  // called once the model is built, before the first cycle (the CLI prints the contact law's
  // fallback warning here, so that input refused while building gets no warning before it)
  std::function<void(const models::BuiltModel&)> on_built;
};

// runs the job; returns the summary written to out/summary.json; throws InputError for bad
// input and std::runtime_error when the simulation stops (what was complete is kept)
nlohmann::json run_wear_job(const WearJob& job);

// the wear loop's options of the job on its built model (law, factor, friction, intervals):
// no outputs, checkpoint or progress; the studies run wear trials through it
wear::WearOptions make_wear_options(const WearJob& job, const models::BuiltModel& built);

// removes the files a wear job writes (a previous run's results and failure records) from
// `dir`; true when there were any
bool clear_wear_outputs(const std::filesystem::path& dir);

// checks cycles, interval, schedule and wear factor; throws InputError with one sentence
void check_wear_job(const WearJob& job);

// runs the jobs concurrently, one per core (or `workers`), and returns their summaries in
// order; rethrows the first job's error after all have stopped. `done` is called after each.
std::vector<nlohmann::json> run_wear_jobs(
    const std::vector<WearJob>& jobs, int workers = 0,
    const std::function<void(size_t, const nlohmann::json&)>& done = {});

}  // namespace kneesim::run
