#include "analysis/study/knee_problem.h"

#include "analysis/run/calibrate_contact_law.h"
#include "models/contact_law_library.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "analysis/run/gait_run.h"
#include "analysis/run/run_outputs.h"
#include "analysis/run/wear_job.h"
#include "engine/errors.h"
#include "engine/simulate.h"
#include "wear/wear_law.h"
#include "wear/wear_loop.h"

namespace kneesim::study {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

std::string value_text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

StudyProblem make_knee_problem(const KneeStudySetup& s) {
  models::Config base = run::load_run_config(s.config, s.sets);
  if (!s.measured.empty()) base.measured_kinematics = std::filesystem::absolute(s.measured).string();
  StudyProblem p;
  if (s.vars.empty()) {
    p.variables = pal2008_variables(base, s.allow_truncation);
  } else {
    for (const auto& v : s.vars) p.variables.push_back(make_variable(base, v, s.allow_truncation));
  }
  for (size_t i = 0; i < p.variables.size(); ++i)
    for (size_t k = 0; k < i; ++k)
      if (p.variables[i].key == p.variables[k].key)
        throw InputError("--var " + p.variables[i].key + " is given twice");
  if (s.wear) {
    if (s.wear_cycles <= 0) throw InputError("--wear-cycles must be positive");
    if (s.wear_updates < 1 || s.wear_updates > 1000)
      throw InputError("--wear-updates = " + std::to_string(s.wear_updates) +
                       " is outside the allowed range 1 to 1000");
    // the wear law of every trial (refuses a law the material has no coefficient for)
    wear::make_wear_law(base.wear, base.material, base.material.friction);
  }
  p.measures = {"ap_rom_mm", "ie_rom_deg", "peak_pressure_MPa"};
  if (s.wear) {
    p.measures.push_back("max_linear_wear_mm");
    p.measures.push_back("gravimetric_wear_mg");
  }
  CurveSpec ap{"ap_mm", "gait_pct", {}, "envelopes.csv"};
  for (int k = 0; k < 100; ++k) ap.x.push_back(k);  // the frames: 0 to 99 % of the cycle
  CurveSpec ie = ap;
  ie.name = "ie_deg";
  p.curves = {ap, ie};
  if (s.wear) {
    CurveSpec lin{"max_linear_wear_mm", "cycles", {0.0}, "wear_envelopes.csv"};
    const long every = std::max(1L, s.wear_cycles / s.wear_updates);
    for (long c = every; c < s.wear_cycles; c += every) lin.x.push_back(static_cast<double>(c));
    lin.x.push_back(static_cast<double>(s.wear_cycles));
    CurveSpec grav = lin;
    grav.name = "gravimetric_wear_mg";
    p.curves.push_back(lin);
    p.curves.push_back(grav);
  }

  // a measured trace for the envelope plot, read (and checked) before any trial
  p.measured = run::read_measured_kinematics(base);

  // the nominal law after every cheap check (first use: calibrated now, a deformable cycle)
  run::ensure_contact_law(base, s.quiet);
  // the nominal model: built once, shared (const) by every trial for its geometry
  auto nominal = std::make_shared<const models::BuiltModel>(models::build_model(base));
  p.contact_law = run::describe_contact_law(base, nominal->model.contact.foundation_modulus * 1e-6);
  const std::vector<StudyVariable> vars = p.variables;
  p.evaluate = [s, vars, nominal, base](const std::vector<double>& x) {
    std::vector<std::string> sets = s.sets;
    for (size_t j = 0; j < vars.size(); ++j) sets.push_back(vars[j].key + "=" + value_text(x[j]));
    models::Config config = run::load_run_config(s.config, sets);
    if (config.contact_law_resolution.needs_calibration) {
      // a trial that varies the material or the implant has no law of its own (a calibration
      // per trial would cost a deformable cycle each): the nominal law's K_eff / K carries over
      models::transfer_contact_law(base, config);
    }
    models::BuiltModel built = models::build_model(config, nominal.get());
    TrialOutcome out;
    // one gait run (the step shortened where the contact outgrew the estimated limit, as
    // `kneesim run` does): the measures of the last cycle
    const double dt_estimated = built.model.dt;
    engine::RunOptions ro;
    ro.cycles = config.cycles;
    const engine::RunResult r = run::simulate_gait(built, ro);
    if (r.step_retries > 0) {
      out.note = "step shortened " + std::to_string(r.step_retries) + "x at the stability "
                 "limit: dt " + value_text(dt_estimated) + " s to " + value_text(built.model.dt) +
                 " s";
    }
    if (r.status != engine::StepStatus::kOk) {
      out.ok = false;
      out.failure = std::string("gait run stopped at t = ") + value_text(r.failed_at) + " s: " +
                    engine::to_string(r.status);
      return out;
    }
    const run::CycleFigures fig = run::calc_cycle_figures(r.frames);
    out.scalars = {fig.ap_rom_mm, fig.ie_rom_deg, fig.peak_pressure_MPa};
    std::vector<double> ap, ie;
    for (const auto& f : r.frames) {
      ap.push_back(f.joint.ap * 1e3);
      ie.push_back(f.joint.ie * kRadToDeg);
    }
    out.curves = {ap, ie};
    if (s.wear) {
      run::WearJob job;
      job.config = config;
      job.cycles = s.wear_cycles;
      job.update_every = std::max(1L, s.wear_cycles / s.wear_updates);
      job.allow_any_wear_factor = true;  // the variable's range was checked at input
      const wear::WearResult w = wear::run_wear(built, run::make_wear_options(job, built));
      if (w.status != engine::StepStatus::kOk) {
        out.ok = false;
        out.failure = "wear run stopped: " + w.message;
        return out;
      }
      const double density = built.material.density_g_per_cm3;  // mg/mm^3
      std::vector<double> lin, grav;
      for (const auto& rec : w.records) {
        lin.push_back(rec.max_depth * 1e3);
        grav.push_back(rec.volume * 1e9 * density);
      }
      out.scalars.push_back(lin.back());
      out.scalars.push_back(grav.back());
      out.curves.push_back(lin);
      out.curves.push_back(grav);
    }
    return out;
  };
  return p;
}

}  // namespace kneesim::study
