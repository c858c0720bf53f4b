// `kneesim particles`: the wear-particle size model (half-space BEM, von Mises criterion) for a
// material pair; writes one row per particle, the per-iteration history, maps for the plots
// and a JSON summary. Runs the steel-steel pair of the particle-size study at 10 N when given
// no arguments.
#include <algorithm>
#include <omp.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "analysis/run/calibrate_contact_law.h"
#include "analysis/run/run_outputs.h"
#include "engine/errors.h"
#include "engine/io/atomic_file.h"
#include "engine/io/json_out.h"
#include "engine/io/plot.h"
#include "engine/io/progress.h"
#include "engine/io/table.h"
#include "engine/simulate.h"
#include "models/build_model.h"
#include "models/config.h"
#include "engine/io/output_folder.h"
#include "analysis/report/command_reports.h"
#include "tools/kneesim/commands.h"
#include "wear/particles/fft.h"
#include "wear/particles/particle_model.h"
#include "wear/particles/particles_config.h"

namespace kneesim::cli {
namespace {

namespace pt = kneesim::particles;

struct ParticlesOptions {
  std::string config;
  std::string pair;
  double load_N = -1.0;
  double contact_pressure_MPa = -1.0;
  std::string out = "kneesim-particles";
  int max_iterations = 0;
  bool no_film = false;
  bool no_plots = false;
  bool no_calibrate = false;
};

std::string map_csv(const std::vector<double>& v, int rows, int cols, double scale) {
  std::string out;
  char buf[32];
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      std::snprintf(buf, sizeof buf, "%.6g", v[static_cast<long>(i) * cols + j] * scale);
      out += buf;
      out += j + 1 < cols ? "," : "\n";
    }
  }
  return out;
}

nlohmann::json size_json(const pt::SizeStats& s) {
  return {{"particles", s.particles},          {"mean_eq_radius_nm", s.eq_radius * 1e9},
          {"mean_length_nm", s.length * 1e9},  {"mean_width_nm", s.width * 1e9},
          {"mean_thickness_nm", s.thickness * 1e9}, {"mean_volume_um3", s.volume * 1e18},
          {"volume_weighted_eq_radius_nm", s.volume_weighted_eq_radius * 1e9},
          {"volume_fraction_eq_diameter_0p1_to_1um", s.active_band_volume_fraction}};
}

nlohmann::json body_json(const pt::BodySpec& b) {
  return {{"material", b.material},
          {"E_GPa", b.elastic.youngs_modulus / 1e9},
          {"nu", b.elastic.poisson_ratio},
          {"hardness_GPa", b.hardness / 1e9},
          {"yield_GPa", b.yield_stress / 1e9},
          {"rq_nm", b.roughness.rq * 1e9},
          {"skewness", b.roughness.skewness},
          {"kurtosis", b.roughness.kurtosis},
          {"correlation_length_nm", b.roughness.correlation_length * 1e9},
          {"lambda_s_nm", b.roughness.lambda_s * 1e9},
          {"peklenik_gamma", b.roughness.gamma},
          {"film_thickness_nm", b.elastic.film_thickness * 1e9},
          {"film_E_GPa", b.elastic.film_modulus / 1e9},
          {"film_yield_GPa", b.film_yield_stress / 1e9},
          {"film_hardness_GPa", b.film_hardness / 1e9},
          {"surface_csv", b.surface_csv}};
}

// A knee pair's contact pressure: the mean peak pressure of `kneesim run` with the pair's insert
// material (built-in implant, default rig and gait, the settled cycle), i.e. of kneesim's rigid
// insert with the same contact law as every command: the law calibrated against the deformable
// insert, or with --no-calibrate the law as specified.
pt::KneeContactPressure knee_contact_pressure(pt::PairName pair, bool no_calibrate) {
  const std::string material = pt::knee_pair_material(pair);
  std::vector<models::Override> overrides = {{"material.name", material}};
  if (no_calibrate) overrides.push_back({"contact.calibration", "\"off\""});
  models::Config config = models::load_config("", overrides);
  run::ensure_contact_law(config);
  if (const std::string& w = config.contact_law_resolution.warning; !w.empty()) {
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  const models::BuiltModel built = models::build_model(config);
  engine::State state = engine::make_initial_state(built.model);
  engine::Data data = engine::make_data(built.model);
  engine::RunOptions ro;
  ro.cycles = config.cycles;
  const engine::RunResult r = engine::simulate(built.model, state, data, ro);
  if (r.status != engine::StepStatus::kOk || r.frames.empty()) {
    throw std::runtime_error("the contact run for the " + material + " insert stopped (" +
                             engine::to_string(r.status) + "); give contact_pressure_MPa");
  }
  const double p = run::calc_cycle_figures(r.frames).mean_peak_pressure_MPa;
  char buf[256];
  const models::ContactLawResolution& law = config.contact_law_resolution;
  std::snprintf(buf, sizeof buf, "kneesim run --set material.name=%s%s: mean peak pressure %.2f MPa "
                "(rigid insert, contact law %s, K %.0f MPa; built-in implant, %s rig)",
                material.c_str(), no_calibrate ? " --no-calibrate" : "", p,
                law.source == "specified" ? "as specified" : ("calibrated, " + law.source).c_str(),
                built.model.contact.foundation_modulus * 1e-6, config.rig_preset.c_str());
  return {p * 1e6, buf};
}

void run_particles(const ParticlesOptions& o) {
  // inputs: config file or pair preset, then the command-line overrides; a knee pair's contact
  // pressure from --contact-pressure-MPa, the config, or a kneesim contact run
  const pt::KneeContactPressureFn knee_pressure = [&o](pt::PairName pair) {
    if (o.contact_pressure_MPa > 0.0) {
      return pt::KneeContactPressure{o.contact_pressure_MPa * 1e6, "--contact-pressure-MPa"};
    }
    return knee_contact_pressure(pair, o.no_calibrate);
  };
  pt::ParticleModelConfig c = [&] {
    if (!o.config.empty()) return pt::read_particle_config(o.config, knee_pressure);
    const pt::PairName pair = pt::parse_pair(o.pair.empty() ? "steel-steel" : o.pair, "--pair");
    if (!pt::is_knee_pair(pair)) {
      if (o.contact_pressure_MPa > 0.0) {
        throw InputError("--contact-pressure-MPa applies to the knee pairs only, not to " +
                         std::string(pt::pair_name(pair)));
      }
      return pt::make_pair_config(pair);
    }
    const pt::KneeContactPressure p = knee_pressure(pair);
    return pt::make_pair_config(pair, p.pressure, p.source);
  }();
  if (!c.contact_pressure_source.empty()) {
    std::printf("%s: contact pressure %.2f MPa from %s\n", c.pair.c_str(),
                c.contact_pressure * 1e-6, c.contact_pressure_source.c_str());
  }
  if (!o.config.empty() && !o.pair.empty()) {
    throw InputError("--pair " + o.pair + " conflicts with the pair of " + o.config +
                     "; give one of them");
  }
  if (o.load_N >= 0.0) c.load = o.load_N;
  if (o.max_iterations > 0) c.max_iterations = o.max_iterations;
  if (o.no_film) c.harder.elastic.film_thickness = c.softer.elastic.film_thickness = 0.0;

  // run
  io::ProgressBar bar("particles " + c.pair);
  const pt::ParticleModelResult r =
      pt::run_particle_model(c, o.config.empty() ? "kneesim particles" : o.config,
                             [&](double f) { bar.update(f); });
  bar.finish();

  // outputs
  const std::filesystem::path dir(o.out);
  io::Table parts;
  parts.columns = {"iteration", "volume_um3", "eq_radius_nm", "length_nm", "width_nm", "thickness_nm",
                   "from_counterface"};
  for (const pt::ParticleRecord& p : r.particles) {
    parts.add_row({double(p.iteration), p.particle.volume * 1e18, p.particle.eq_radius * 1e9,
                   p.particle.length * 1e9, p.particle.width * 1e9, p.particle.thickness * 1e9,
                   p.source == pt::ParticleSource::kCounterface ? 1.0 : 0.0});
  }
  io::write_csv(dir / "particles.csv", parts);
  io::Table its;
  its.columns = {"iteration", "particles", "counterface_particles", "mean_eq_radius_nm", "max_pressure_MPa", "load_N",
                 "contact_fraction", "capped_fraction", "cg_iterations", "cg_converged",
                 "stress_levels", "particle_volume_um3", "plastic_volume_um3",
                 "track_rq_nm", "track_mean_wear_nm", "counterface_plastic_volume_um3",
                 "counterface_rq_nm"};
  for (const pt::IterationRecord& it : r.iterations) {
    its.add_row({double(it.iteration), double(it.particles), double(it.counterface_particles),
                 it.mean_eq_radius * 1e9,
                 it.max_pressure / 1e6, it.load, it.contact_fraction, it.capped_fraction,
                 double(it.cg_iterations), double(it.contact_converged),
                 double(it.stress_levels), it.particle_volume * 1e18,
                 it.plastic_volume * 1e18, it.track_rq * 1e9, it.track_mean_wear * 1e9,
                 it.counterface_plastic_volume * 1e18, it.counterface_rq * 1e9});
  }
  io::write_csv(dir / "iterations.csv", its);
  io::write_file_atomic(dir / "pressure_map_MPa.csv",
                        map_csv(r.pressure, c.grid.nx, c.grid.ny, 1e-6));
  io::write_file_atomic(dir / "von_mises_section_MPa.csv",
                        map_csv(r.von_mises_section, r.section_levels, c.grid.nx, 1e-6));

  nlohmann::json j = size_json(r.steady);
  j["iterations"] = r.iterations.size();
  j["seconds"] = r.seconds;
  j["steady_state"] = r.steady_state;
  j["steady_from_iteration"] = r.steady_from;
  // contacts that ended at the CG cap (placed plastically; iterations.csv: cg_converged = 0)
  j["contacts_unconverged"] = std::count_if(r.iterations.begin(), r.iterations.end(),
                                            [](const pt::IterationRecord& it) { return !it.contact_converged; });
  const pt::RunLengths run = pt::resolve_run_lengths(c);
  j["run"] = {{"pass_iterations", run.pass}, {"block_iterations", run.block},
              {"min_iterations", run.min_iterations}, {"max_iterations", run.max_iterations},
              {"steady_tolerance", c.steady_tolerance},
              {"roughness_tolerance", c.roughness_tolerance},
              {"contact_max_iterations", c.contact_max_iterations},
              {"track_factor", c.track_factor}, {"slide_cells", c.slide_cells}};
  if (!r.iterations.empty()) {
    j["track_rq_nm"] = {{"initial", r.initial_track_rq * 1e9},
                        {"final", r.iterations.back().track_rq * 1e9}};
    j["track_mean_wear_nm"] = r.iterations.back().track_mean_wear * 1e9;
    j["counterface_rq_nm"] = {{"initial", r.initial_counterface_rq * 1e9},
                              {"final", r.iterations.back().counterface_rq * 1e9}};
  }
  j["all_particles"] = size_json(r.all);
  j["counterface_particles"] = size_json(r.steady_counterface);
  j["pair"] = c.pair;
  j["load_N"] = c.load;
  j["window_load_N"] = pt::window_load(c);
  j["friction"] = c.friction;
  if (c.contact_pressure > 0.0) {
    j["contact_pressure_MPa"] = c.contact_pressure * 1e-6;
    j["contact_pressure_source"] = c.contact_pressure_source;
  }
  j["plastic_deformation"] = c.plastic_deformation;
  const pt::PlasticFlowRule flow = pt::make_plastic_flow_rule(c);
  j["plastic_flow"] = {{"pressure_cap_GPa", flow.hardness / 1e9},
                       {"worn_body_flows", flow.worn_flows},
                       {"counterface_flows", flow.counterface_flows},
                       {"counterface_share", flow.counterface_share}};
  j["cylinder_radius_mm"] = c.cylinder_radius * 1e3;
  j["cylinder_length_mm"] = c.cylinder_length * 1e3;
  j["grid"] = {{"nx", c.grid.nx}, {"ny", c.grid.ny}, {"dx_nm", c.grid.dx * 1e9},
               {"nz", c.nz}, {"dz_nm", c.dz * 1e9}, {"refine", c.refine}};
  j["harder"] = body_json(c.harder);
  j["softer"] = body_json(c.softer);
  j["sources"] = c.sources;
  j["fft_backend"] = pt::Fft2::backend();
  j["threads"] = omp_get_max_threads();
  j["section_dz_nm"] = c.dz * 1e9;
  j["dx_nm"] = c.grid.dx * 1e9;
  io::write_json(dir / "summary.json", j);
  report::write_particles_report(dir);

  std::printf("%s at %g N: %ld particles in %zu iterations (%s), mean eq. radius %.0f nm, "
              "length %.0f nm, width %.0f nm, thickness %.0f nm (volume-weighted radius %.0f nm, "
              "%.0f %% of the volume at diameters 0.1-1 um); %.1f s -> %s\n",
              c.pair.c_str(), c.load, r.steady.particles, r.iterations.size(),
              r.steady_state ? "steady" : "not steady at the iteration limit",
              r.steady.eq_radius * 1e9, r.steady.length * 1e9, r.steady.width * 1e9,
              r.steady.thickness * 1e9, r.steady.volume_weighted_eq_radius * 1e9,
              100.0 * r.steady.active_band_volume_fraction, r.seconds, dir.string().c_str());
  if (!o.no_plots) io::run_plot("particles.py", {dir.string()});
}

}  // namespace

void add_particles_command(CLI::App& app) {
  auto opts = std::make_shared<ParticlesOptions>();
  CLI::App* cmd = app.add_subcommand(
      "particles",
      "Wear-particle sizes from a rough-contact half-space BEM with the von Mises detachment "
      "criterion (default: steel-steel at 10 N, the particle-size study's case)");
  cmd->add_option("config", opts->config, "TOML config (see docs/particles.md)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--pair", opts->pair,
                  "steel-steel|steel-brass|uhmwpe-cocr|peek-cocr|cfrpeek-cocr");
  cmd->add_option("--load-N", opts->load_N, "normal load on the cylinder [N]")
      ->check(finite_range(1e-3, 1e6));
  cmd->add_option("--contact-pressure-MPa", opts->contact_pressure_MPa,
                  "knee pairs: the Hertz peak pressure the cylinder is sized to (default: the "
                  "mean peak pressure of `kneesim run` with the insert material)")
      ->check(finite_range(0.1, 10000.0));
  cmd->add_option("--out", opts->out, "output folder")->capture_default_str();
  cmd->add_option("--max-iterations", opts->max_iterations, "wear-loop iteration limit (default: 40 blocks of two passes of the track, 640 "
                  "iterations at the defaults; the loop stops earlier at the run-in steady state)")
      ->check(whole_range(1, 1e6));
  cmd->add_flag("--no-film", opts->no_film, "drop transfer films (homogeneous model)");
  cmd->add_flag("--no-plots", opts->no_plots, "skip the PNG plots");
  add_no_calibrate_flag(cmd, opts->no_calibrate);
  cmd->callback([opts]() {
    io::check_output_folder(opts->out);  // before any work
    run_particles(*opts);
  });
}

}  // namespace kneesim::cli
