// `kneesim bor`: the block-on-ring wear model run forward at one load. --model analytic (the
// default): the semi-analytic model (physics.md section 7) with the steady-state Archard law or
// one of the named wear-law extensions. --model fe: the numerical model (wear/bor/bor_fe.h),
// a rigid ring on the deformable hex8 block with Archard wear and a geometry update every
// --update-every cycles. Both write bor.csv with the same columns (one row every --step cycles
// from 0 to --cycles inclusive), summary.json and bor.png; fe adds bor_fe.csv (the solver's
// figures per row).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "engine/errors.h"
#include "analysis/report/command_reports.h"
#include "engine/io/json_out.h"
#include "engine/io/plot.h"
#include "engine/io/table.h"
#include "engine/io/output_folder.h"
#include "tools/kneesim/bor_options.h"
#include "tools/kneesim/commands.h"
#include "wear/bor/bor_fe.h"
#include "wear/bor/bor_simulation.h"

namespace kneesim::cli {
namespace {

struct BorOptions {
  double load_N = 225.0;
  double cycles = 200000.0;
  double k_mm3_per_Nmm = 4.1e-10;
  double step = 10000.0;
  std::string effect = "none";
  std::vector<std::string> effect_params;
  std::string out = "kneesim-bor";
  std::string model = "analytic";
  double fe_element_mm = 0.1;
  double fe_axial_element_mm = 1.0;
  double update_every = 10000.0;
  int fe_max_steps = 200000;
  int threads = 1;
  BorRigOptions rig;
};

void check(bool ok, const std::string& sentence) {
  if (!ok) throw InputError("command line: " + sentence);
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

void run_bor(const BorOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  // validate everything before computing anything
  check(std::isfinite(o.load_N) && o.load_N > 0.0 && o.load_N <= 1e4,
        "--load-N = " + fmt("%g", o.load_N) + " N is outside the allowed range (0, 10000] N.");
  check(o.cycles >= 1.0 && o.cycles <= 1e9 && std::floor(o.cycles) == o.cycles,
        "--cycles = " + fmt("%g", o.cycles) + " must be a whole number in [1, 1e9].");
  check(o.step >= 1.0 && std::floor(o.step) == o.step && o.step <= o.cycles,
        "--step = " + fmt("%g", o.step) + " must be a whole number in [1, --cycles = " +
            fmt("%g", o.cycles) + "].");
  check(o.cycles / o.step <= 1e5, "--cycles / --step = " + fmt("%g", o.cycles / o.step) +
                                      " rows is more than the allowed 100000; raise --step.");
  check(o.k_mm3_per_Nmm >= 1e-12 && o.k_mm3_per_Nmm <= 1e-6,
        "--k = " + fmt("%g", o.k_mm3_per_Nmm) +
            " mm^3/(N mm) is outside the allowed range [1e-12, 1e-6] mm^3/(N mm).");
  const bor::BorRig rig = make_bor_rig(o.rig);
  const bor::BorWearLaw law = bor::parse_wear_law(o.effect, "command line --effect");
  bor::BorWearParams params;
  params.k = o.k_mm3_per_Nmm * 1e-6;  // mm^3/(N mm) = mm^2/N -> m^2/N
  apply_effect_params(law, o.effect_params, params);

  std::vector<double> cycles;
  for (double n = 0.0; n < o.cycles; n += o.step) cycles.push_back(n);
  cycles.push_back(o.cycles);
  check(o.model == "analytic" || o.model == "fe",
        "--model = '" + o.model + "' is not a block-on-ring model; allowed: analytic, fe.");
  const bool fe = o.model == "fe";
  check(!fe || law == bor::BorWearLaw::archard,
        "--effect = '" + o.effect + "' is not available with --model fe; allowed: none.");
  bor::BorFeOptions fe_options;
  fe_options.element_size = 1e-3 * o.fe_element_mm;
  fe_options.axial_element_size = 1e-3 * o.fe_axial_element_mm;
  fe_options.update_cycles = o.update_every;
  fe_options.max_relax_steps = o.fe_max_steps;
  fe_options.threads = o.threads;
  // checked with either model: a bad value is refused, not silently unused
  bor::check_bor_fe_options(fe_options, rig);

  const std::filesystem::path out = o.out;
  std::vector<bor::BorRow> rows;
  std::vector<bor::BorFeRow> fe_rows;
  bor::BorFeMeshInfo fe_info;
  if (fe) {
    fe_rows = bor::simulate_bor_fe(
        rig, o.load_N, params, cycles, fe_options,
        [&](const bor::BorFeRow& r, const bor::BorFeMeshInfo& info) {
          fe_info = info;
          std::fprintf(stderr, "  %8.0f cycles: volume %.4f mm^3, depth %.4f mm, width %.3f mm, "
                       "%d relaxation steps\n", r.row.cycles, r.row.volume * 1e9,
                       r.row.depth * 1e3, r.row.contact_width * 1e3, r.relax_steps);
        });
    for (const auto& r : fe_rows) rows.push_back(r.row);
    io::Table t;
    t.columns = {"cycles", "volume_mm3", "wear_sum_volume_mm3", "depth_mm", "contact_width_mm",
                 "second_moment_half_width_mm", "mean_pressure_MPa", "peak_pressure_MPa",
                 "ring_reaction_N", "relaxation_steps", "kinetic_ratio"};
    for (const auto& r : fe_rows) {
      t.add_row({r.row.cycles, r.row.volume * 1e9, r.wear_sum_volume * 1e9, r.row.depth * 1e3,
                 r.row.contact_width * 1e3, r.hertz_half_width * 1e3,
                 r.row.mean_pressure * 1e-6, r.peak_pressure * 1e-6, r.contact_force,
                 static_cast<double>(r.relax_steps), r.kinetic_ratio});
    }
    io::write_csv(out / "bor_fe.csv", t);
  } else {
    rows = bor::simulate_bor(rig, o.load_N, law, params, cycles);
  }
  const bor::BorContact unworn = bor::solve_bor_contact(rig, o.load_N, 0.0);
  io::Table table;
  table.columns = {"cycles", "volume_mm3", "depth_mm", "contact_width_mm", "mean_pressure_MPa"};
  for (const auto& r : rows) {
    table.add_row({r.cycles, r.volume * 1e9, r.depth * 1e3, r.contact_width * 1e3,
                   r.mean_pressure * 1e-6});
  }
  io::write_csv(out / "bor.csv", table);

  const auto& last = rows.back();
  nlohmann::json s;
  s["model"] = o.model;
  s["load_N"] = o.load_N;
  s["cycles"] = o.cycles;
  s["k_mm3_per_Nmm"] = o.k_mm3_per_Nmm;
  s["effect"] = o.effect == "none" ? "none" : std::string(bor::wear_law_name(law));
  nlohmann::json ep = nlohmann::json::object();
  for (const auto& name : bor::wear_law_param_names(law)) {
    ep[name] = bor::get_wear_param(params, name);
  }
  s["effect_params"] = ep;
  s["volume_mm3"] = last.volume * 1e9;
  s["depth_mm"] = last.depth * 1e3;
  s["contact_width_mm"] = last.contact_width * 1e3;
  s["mean_pressure_MPa"] = last.mean_pressure * 1e-6;
  s["wear_rate_mm3_per_Mc"] = last.volume * 1e9 / o.cycles * 1e6;
  if (fe) {
    s["unworn_half_width_mm"] = fe_rows.front().row.contact_width * 0.5e3;
    s["unworn_second_moment_half_width_mm"] = fe_rows.front().hertz_half_width * 1e3;
    s["unworn_mean_pressure_MPa"] = fe_rows.front().row.mean_pressure * 1e-6;
    s["unworn_peak_pressure_MPa"] = fe_rows.front().peak_pressure * 1e-6;
    s["update_every_cycles"] = o.update_every;
    s["fe_element_mm"] = o.fe_element_mm;
    s["fe_axial_element_mm"] = o.fe_axial_element_mm;
    s["fe_elements_half_block"] = fe_info.elements;
    s["fe_step_ns"] = fe_info.dt * 1e9;
    s["fe_damping_per_s"] = fe_info.damping_alpha;
    s["threads"] = o.threads;
  } else {
    s["unworn_half_width_mm"] = unworn.contact_width * 0.5e3;
    s["unworn_penetration_mm"] = unworn.penetration * 1e3;
    s["unworn_mean_pressure_MPa"] = unworn.mean_pressure * 1e-6;
  }
  s["foundation_constant_MPa_per_mm"] = bor::foundation_constant(rig) * 1e-9;
  s["sliding_distance_per_cycle_mm"] = bor::sliding_distance_per_cycle(rig) * 1e3;
  s["sarkar_factor"] = bor::sarkar_factor(rig.friction);
  s["seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::write_json(out / "summary.json", s);
  report::write_bor_report(out);
  io::run_plot("bor.py", {(out / "bor.csv").string(), (out / "bor.png").string(),
                          "load " + fmt("%g", o.load_N) + " N, " + std::string(s["effect"]) +
                              (fe ? ", FE model" : "")});
  std::printf("block-on-ring (%s) %g N, %g cycles (%s): volume %.4f mm^3, depth %.4f mm, contact width "
              "%.3f mm, mean pressure %.3f MPa -> %s\n",
              o.model.c_str(), o.load_N, o.cycles, std::string(s["effect"]).c_str(), last.volume * 1e9,
              last.depth * 1e3, last.contact_width * 1e3, last.mean_pressure * 1e-6,
              out.string().c_str());
}

}  // namespace

void add_bor_command(CLI::App& app) {
  auto opt = std::make_shared<BorOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bor", "Block-on-ring wear model, semi-analytic or FE (Hussin 2024 rig; docs/theory.md)");
  cmd->add_option("--model", opt->model,
                  "analytic (Winkler block, docs/theory.md) or fe (rigid ring on the "
                  "deformable hex8 block, Archard only; docs/deformable.md)")
      ->capture_default_str();
  cmd->add_option("--update-every", opt->update_every,
                  "fe: cycles between geometry updates")
      ->capture_default_str()->check(whole_range(1, 1e9));
  cmd->add_option("--fe-element-mm", opt->fe_element_mm,
                  "fe: element size under the ring [mm]")
      ->capture_default_str()->check(finite_number("[0.02, 1] mm"));
  cmd->add_option("--fe-axial-element-mm", opt->fe_axial_element_mm,
                  "fe: element size along the ring axis [mm]")
      ->capture_default_str()->check(finite_number("[--fe-element-mm, half the ring width] mm"));
  cmd->add_option("--fe-max-steps", opt->fe_max_steps,
                  "fe: relaxation steps allowed per geometry")
      ->capture_default_str()->check(whole_range(100, 1e8));
  cmd->add_option("--threads", opt->threads, "fe: threads of the element loop")
      ->capture_default_str()->check(whole_range(1, 64));
  cmd->add_option("--load-N", opt->load_N, "normal load [N]")
      ->capture_default_str()->check(finite_number("(0, 10000] N"));
  cmd->add_option("--cycles", opt->cycles, "final cycle count [cycles]")
      ->capture_default_str()->check(finite_number("a whole number in [1, 1e9]"));
  cmd->add_option("--k", opt->k_mm3_per_Nmm, "steady-state wear factor k_D [mm^3/(N mm)]")
      ->capture_default_str()->check(finite_number("[1e-12, 1e-6] mm^3/(N mm)"));
  cmd->add_option("--step", opt->step, "cycles between output rows")
      ->capture_default_str()->check(finite_number("a whole number in [1, --cycles]"));
  cmd->add_option("--effect", opt->effect,
                  "wear law: none, running_in, pressure_dependent_wear, creep, incubation")
      ->capture_default_str();
  cmd->add_option("--effect-param", opt->effect_params,
                  "effect parameter name=value (running_in_excess, running_in_cycles, "
                  "pressure_exponent, reference_pressure_MPa, creep_ratio, creep_time_s, "
                  "incubation_cycles)");
  cmd->add_option("--out", opt->out, "output folder")->capture_default_str();
  add_bor_rig_options(cmd, opt->rig);
  cmd->callback([opt] {
    io::check_output_folder(opt->out);  // before any work
    run_bor(*opt);
  });
}

}  // namespace kneesim::cli
