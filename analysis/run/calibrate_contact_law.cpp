#include "analysis/run/calibrate_contact_law.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <unistd.h>

#include "analysis/run/contact_calibration.h"
#include "analysis/run/gait_run.h"
#include "engine/contact_law.h"
#include "engine/errors.h"
#include "engine/io/atomic_file.h"
#include "engine/io/json_out.h"
#include "engine/io/output_folder.h"
#include "engine/io/plot.h"
#include "engine/io/table.h"
#include "models/contact_law_file.h"
#include "models/contact_law_key.h"
#include "models/build_model.h"
#include "models/contact_law_library.h"

namespace kneesim::run {
namespace {

constexpr double kSearchLo = 0.01, kSearchHi = 10.0;  // K_eff / K
constexpr double kExponentLo = 0.3, kExponentHi = 1.5;  // n of p = K_eff g^n

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}


// the deformable reference's mesh in words, for the provenance; its surfaces when they differ
// from the rigid runs' (`rigid`)
std::string describe_mesh(const models::Config& c, const models::Config& rigid) {
  char buf[512];
  if (c.deformable_refine == "contact") {
    std::snprintf(buf, sizeof buf,
                  "%g mm where the cycle's contact occurs (margin %g mm), %g mm outside, "
                  "%d layers, grading %g",
                  c.deformable_element_size_mm, c.deformable_refine_margin_mm,
                  c.deformable_outer_element_size_mm, c.deformable_layers, c.deformable_grading);
  } else {
    std::snprintf(buf, sizeof buf, "uniform %g mm, %d layers, grading %g",
                  c.deformable_element_size_mm, c.deformable_layers, c.deformable_grading);
  }
  std::string text = buf;
  if (c.edge_length_mm != rigid.edge_length_mm || c.sdf_spacing_mm != rigid.sdf_spacing_mm) {
    std::snprintf(buf, sizeof buf,
                  "; surfaces %g mm facets, distance field %g mm (the rigid runs: %g mm, %g mm)",
                  c.edge_length_mm, c.sdf_spacing_mm, rigid.edge_length_mm, rigid.sdf_spacing_mm);
    text += buf;
  }
  return text;
}

// the deformable reference's config: the calibration's, on the job's surfaces
models::Config reference_config(const models::Config& base, const ContactCalibrationJob& job) {
  models::Config c = base;
  if (job.reference_edge_length_mm > 0.0) {
    if (base.implant_kind != "generic") {
      throw InputError("--reference-edge-mm " + number(job.reference_edge_length_mm) +
                       " sets the built-in implant's triangulation; the implant is \"" +
                       base.implant_kind + "\" (imported meshes keep their own facets).");
    }
    c.edge_length_mm = job.reference_edge_length_mm;
  }
  if (job.reference_sdf_spacing_mm > 0.0) c.sdf_spacing_mm = job.reference_sdf_spacing_mm;
  return c;
}

// a finished deformable run given with --deformable-from must be of the calibration's settings
void check_deformable_run(const std::filesystem::path& dir, const models::Config& c) {
  const std::filesystem::path file = dir / "summary.json";
  nlohmann::json s;
  try {
    s = nlohmann::json::parse(io::read_file(file));
  } catch (const std::exception&) {
    throw InputError(file.string() + ": --deformable-from must name a finished kneesim run "
                     "(its summary.json is missing or unreadable).");
  }
  auto differs = [&](const char* key, const nlohmann::json& want) {
    if (!s.contains(key) || s[key] != want) {
      throw InputError(file.string() + ": --deformable-from names a run with " + key + " = " +
                       (s.contains(key) ? s[key].dump() : std::string("(none)")) +
                       ", the calibration needs " + want.dump() +
                       " (a finished deformable run of the same config and material).");
    }
  };
  differs("status", "complete");
  differs("insert", "deformable");
  differs("material", c.material.name);
  differs("implant", c.implant_kind);
  differs("rig_preset", c.rig_preset);
  // (runs before the key was recorded lack it: their period is not known, not refused)
  if (s.contains("gait_period_s")) differs("gait_period_s", c.period_s);
  differs("deformable_element_size_mm", c.deformable_element_size_mm);
  differs("deformable_layers", c.deformable_layers);
  differs("deformable_grading", c.deformable_grading);
  differs("deformable_refine", c.deformable_refine);
  differs("sdf_spacing_mm", c.sdf_spacing_mm);
  if (c.implant_kind == "generic") differs("implant_edge_length_mm", c.edge_length_mm);
}

}  // namespace

void check_exponent_inside_search(double n_fit, const std::string& material,
                                  const std::string& implant, const std::filesystem::path& out) {
  if (n_fit < 1.02 * kExponentLo || n_fit > kExponentHi / 1.02) {
    throw InputError("the contact-law fit for material \"" + material + "\" on implant \"" +
                     implant + "\" ended at the search bound of the exponent n = " +
                     number(n_fit) + " (search " + number(kExponentLo) + " to " +
                     number(kExponentHi) + "): no law written; the runs are in " + out.string());
  }
}

void check_fit_inside_search(double k_fit, double k_spec, const std::string& material,
                             const std::string& implant, const std::filesystem::path& out) {
  const double lo = kSearchLo * k_spec, hi = kSearchHi * k_spec;
  if (k_fit < 1.05 * lo || k_fit > hi / 1.05) {
    throw InputError("the contact-law fit for material \"" + material + "\" on implant \"" +
                     implant + "\" ended at the search bound K_eff = " + number(k_fit) +
                     " MPa (search " + number(lo) + " to " + number(hi) + " MPa, " +
                     number(kSearchLo) + " to " + number(kSearchHi) +
                     " times the modulus that gives the law as specified's pressure at the strain " +
                     number(kSearchReferenceStrain) + " with the fitted exponent): no law written; "
                     "the runs are in " + out.string());
  }
}

double modulus_search_reference(double k_spec, double exponent) {
  return k_spec * std::pow(kSearchReferenceStrain, 1.0 - exponent);
}

ContactCalibrationReport calibrate_contact_law(const ContactCalibrationJob& job) {
  namespace fs = std::filesystem;
  const fs::path& out = job.out;
  if (!job.config.contact_law_file.empty() || job.config.contact_foundation_modulus_MPa > 0.0) {
    throw InputError("the config names a contact law (contact.law_file or "
                     "contact.foundation_modulus_MPa); calibrate from the law as specified "
                     "(remove it).");
  }
  const models::Config base = models::make_calibration_config(job.config, /*own_reference=*/true);
  const models::ContactLawKey key = models::make_contact_law_key(base);
  const models::Config reference = reference_config(base, job);
  const std::string reference_mesh = describe_mesh(reference, base);
  const double k_spec_MPa =
      engine::foundation_modulus(base.material.elastic_modulus_MPa, base.material.poisson);
  io::check_output_folder(out);

  // the deformable insert over one cycle (or a finished run of the same settings)
  double deformable_seconds = 0.0;
  int deformable_elements = 0;
  fs::path deformable_csv;
  if (job.deformable_from.empty()) {
    GaitRunJob run;
    run.config = reference;
    run.config.insert_kind = "deformable";
    run.config.cycles = 1;
    run.config.contact_law_resolution = {};
    run.config.contact_law_resolution.source = "unused";
    run.out = out / "deformable";
    run.quiet = job.quiet;
    run.plots = job.plots;
    if (!job.quiet) {
      std::fprintf(stderr, "calibrate-contact: deformable insert (%s), 1 cycle\n",
                   reference_mesh.c_str());
    }
    const GaitRunReport r = run_gait_job(run);
    deformable_seconds = r.seconds;
    deformable_elements = r.summary.value("solid_elements", 0);
    deformable_csv = run.out / "kinematics.csv";
  } else {
    check_deformable_run(job.deformable_from, reference);
    deformable_csv = job.deformable_from / "kinematics.csv";
    const auto s = nlohmann::json::parse(io::read_file(job.deformable_from / "summary.json"));
    deformable_seconds = s.value("seconds_per_cycle", 0.0);
    deformable_elements = s.value("solid_elements", 0);
  }
  const PressureTrace deformable = read_pressure_trace(deformable_csv);

  // a rigid run at a foundation modulus (0: the material's), its trace and seconds per cycle
  auto rigid_run = [&](double modulus_MPa, double exponent, const fs::path& dir, double* seconds) {
    GaitRunJob run;
    run.config = base;
    run.config.contact_foundation_modulus_MPa = modulus_MPa;
    run.config.contact_law_exponent = exponent;
    run.config.contact_law_resolution = {};
    run.config.contact_law_resolution.source = modulus_MPa > 0.0 ? "modulus" : "specified";
    run.out = dir;
    run.quiet = true;
    run.plots = false;
    const GaitRunReport r = run_gait_job(run);
    if (seconds) *seconds = r.seconds / run.config.cycles;
    return read_pressure_trace(dir / "kinematics.csv");
  };
  double rigid_seconds = 0.0;
  const PressureTrace specified =
      rigid_run(0.0, base.contact_law_exponent, out / "rigid", &rigid_seconds);

  // two parameters: for each exponent n (outer golden section) the modulus that fits best
  // (inner); the modulus sets how deep the femur sinks for the load, the exponent the shape of
  // the patch's pressure (its peak over its mean), so the pair can match peak and mean pressure
  // where one modulus trades them against each other
  int evaluations = 0;
  struct Fit {
    double k = 0.0, objective = 1e300;
  };
  auto fit_modulus = [&](double n) {
    // K_eff and n trade against each other (the stance strains are about 0.01): the modulus is
    // searched around the one that gives the law as specified's pressure there
    const double k_ref = modulus_search_reference(k_spec_MPa, n);
    const double lo = kSearchLo * k_ref, hi = kSearchHi * k_ref;
    int inner = 0;
    Fit best;
    minimize_log_golden(
        [&](double k) {
          const auto t = rigid_run(k, n, out / "fit", nullptr);
          const auto e = compare_traces(t, deformable, kFitWindowLo, kFitWindowHi);
          if (!job.quiet) {
            std::fprintf(stderr, "calibrate-contact: n %.3f, K %.1f MPa: peak %.3f, mean %.3f "
                         "(RMS, 0-30 %%)\n", n, k, e.peak, e.mean);
          }
          const double objective = e.peak * e.peak + e.mean * e.mean;
          if (objective < best.objective) best = {k, objective};
          return objective;
        },
        lo, hi, 0.01, inner);
    evaluations += inner;
    return best;
  };
  int outer = 0;
  Fit best;
  double n_fit = job.exponent;
  if (job.exponent > 0.0) {
    best = fit_modulus(job.exponent);
  } else {
    minimize_log_golden(
        [&](double n) {
          const Fit f = fit_modulus(n);
          if (f.objective < best.objective) {
            best = f;
            n_fit = n;
          }
          return f.objective;
        },
        kExponentLo, kExponentHi, 0.02, outer);
  }
  const double k_fit = best.k;
  fs::remove_all(out / "fit");
  const double k_ref = modulus_search_reference(k_spec_MPa, n_fit);
  const double lo = kSearchLo * k_ref, hi = kSearchHi * k_ref;
  check_fit_inside_search(k_fit, k_ref, base.material.name, models::implant_identity(base), out);
  if (job.exponent <= 0.0) {
    check_exponent_inside_search(n_fit, base.material.name, models::implant_identity(base), out);
  }
  double calibrated_seconds = 0.0;
  const PressureTrace calibrated =
      rigid_run(k_fit, n_fit, out / "rigid_calibrated", &calibrated_seconds);

  const TraceErrors held_spec = compare_traces(specified, deformable, kHeldOutLo, kHeldOutHi);
  const TraceErrors held_cal = compare_traces(calibrated, deformable, kHeldOutLo, kHeldOutHi);
  const WindowFigures st_def = calc_window_figures(deformable, kStanceLo, kStanceHi);
  const WindowFigures st_spec = calc_window_figures(specified, kStanceLo, kStanceHi);
  const WindowFigures st_cal = calc_window_figures(calibrated, kStanceLo, kStanceHi);

  models::CalibratedContactLaw law;
  law.material = base.material.name;
  law.implant = models::implant_identity(base);
  law.key = key;
  law.law = base.contact_law;
  law.foundation_modulus_MPa = k_fit;
  law.exponent = n_fit;
  law.specified_modulus_MPa = k_spec_MPa;
  law.fitted_on = std::string(job.exponent > 0.0 ? "modulus (exponent fixed)" : "modulus and exponent") +
                  " on stance 0-30 % peak and mean pressure of the deformable insert (" +
                  reference_mesh + "), rig " + base.rig_preset;
  char date[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
  auto& p = law.provenance;
  p = {{"command", models::toml_quoted(job.command)},
       {"date", models::toml_quoted(date)},
       {"load_case", models::toml_quoted("rig " + base.rig_preset + ", gait " +
                            fs::path(base.gait_file).filename().string() +
                            "; rigid 2 cycles, deformable 1 cycle")},
       {"deformable_mesh", models::toml_quoted(reference_mesh)},
       {"deformable_elements", std::to_string(deformable_elements)},
       {"reference_sdf_spacing_mm", number(reference.sdf_spacing_mm)},
       {"modulus_ratio", number(k_fit / k_spec_MPa)},
       {"search_range_MPa", models::toml_quoted(number(lo) + " to " + number(hi))},
       {"exponent_search", models::toml_quoted(job.exponent > 0.0 ? "fixed (--exponent)"
                                               : number(kExponentLo) + " to " + number(kExponentHi))},
       {"fit_evaluations", std::to_string(evaluations)},
       {"fit_window_pct", models::toml_quoted("0-30")},
       {"held_out_window_pct", models::toml_quoted("30-60")},
       {"held_out_peak_rms_specified", number(held_spec.peak)},
       {"held_out_peak_rms_calibrated", number(held_cal.peak)},
       {"held_out_mean_rms_specified", number(held_spec.mean)},
       {"held_out_mean_rms_calibrated", number(held_cal.mean)},
       {"held_out_area_rms_specified", number(held_spec.area)},
       {"held_out_area_rms_calibrated", number(held_cal.area)},
       {"stance_peak_MPa_deformable", number(st_def.peak_MPa)},
       {"stance_peak_MPa_specified", number(st_spec.peak_MPa)},
       {"stance_peak_MPa_calibrated", number(st_cal.peak_MPa)},
       {"stance_mean_peak_MPa_deformable", number(st_def.mean_peak_MPa)},
       {"stance_mean_peak_MPa_specified", number(st_spec.mean_peak_MPa)},
       {"stance_mean_peak_MPa_calibrated", number(st_cal.mean_peak_MPa)},
       {"stance_mean_MPa_deformable", number(st_def.mean_MPa)},
       {"stance_mean_MPa_specified", number(st_spec.mean_MPa)},
       {"stance_mean_MPa_calibrated", number(st_cal.mean_MPa)},
       {"stance_area_mm2_deformable", number(st_def.area_mm2)},
       {"stance_area_mm2_specified", number(st_spec.area_mm2)},
       {"stance_area_mm2_calibrated", number(st_cal.area_mm2)},
       {"deformable_seconds_per_cycle", number(deformable_seconds)},
       {"rigid_seconds_per_cycle", number(calibrated_seconds)}};
  if (reference.implant_kind == "generic") {
    p.push_back({"reference_edge_length_mm", number(reference.edge_length_mm)});
  }
  models::write_contact_law_file(out / "contact_law.toml", law);

  write_pressure_comparison(out / "comparison.csv", deformable, specified, calibrated);

  nlohmann::json s;
  s["material"] = law.material;
  s["implant"] = law.implant;
  s["key"] = key.key;
  s["law"] = base.contact_law;
  s["specified_modulus_MPa"] = k_spec_MPa;
  s["calibrated_modulus_MPa"] = k_fit;
  s["modulus_ratio"] = k_fit / k_spec_MPa;
  s["calibrated_exponent"] = n_fit;
  s["specified_exponent"] = base.contact_law_exponent;
  s["exponent_search"] = {kExponentLo, kExponentHi};
  s["search_range_MPa"] = {lo, hi};
  s["fit_at_search_bound"] = false;
  s["fit_evaluations"] = evaluations;
  s["deformable_mesh"] = reference_mesh;
  if (reference.implant_kind == "generic") s["reference_edge_length_mm"] = reference.edge_length_mm;
  s["reference_sdf_spacing_mm"] = reference.sdf_spacing_mm;
  s["deformable_elements"] = deformable_elements;
  s["deformable_element_mm"] = base.deformable_element_size_mm;
  add_window_errors(s, "rigid_as_specified", specified, deformable);
  add_window_errors(s, "rigid_calibrated", calibrated, deformable);
  s["stance_figures"] = {{"deformable", window_figures_json(st_def)},
                         {"rigid_as_specified", window_figures_json(st_spec)},
                         {"rigid_calibrated", window_figures_json(st_cal)}};
  s["seconds_per_cycle"] = {{"deformable", deformable_seconds},
                            {"rigid_as_specified", rigid_seconds},
                            {"rigid_calibrated", calibrated_seconds}};
  s["rigid_over_deformable_time"] = deformable_seconds > 0 ? rigid_seconds / deformable_seconds : 0.0;
  io::write_json(out / "summary.json", s);
  if (job.plots) {
    io::run_plot("calibrate.py", {(out / "comparison.csv").string(),
                                  (out / "calibration.png").string(), law.material});
  }
  return {law, s};
}

bool ensure_contact_law(models::Config& config, bool quiet) {
  namespace fs = std::filesystem;
  if (!config.contact_law_resolution.needs_calibration || config.insert_kind == "deformable") {
    return false;
  }
  // meshes the rig cannot use are refused as themselves, before the calibration's minutes (which
  // would otherwise report them as a failed calibration)
  models::load_implant(config);
  const std::string implant = models::implant_identity(config);
  const std::string what = "implant \"" + implant + "\", material \"" + config.material.name + "\"";
  if (!quiet) {
    if (!config.contact_law_resolution.note.empty()) {
      std::fprintf(stderr, "kneesim: %s\n", config.contact_law_resolution.note.c_str());
    }
    std::fprintf(stderr,
                 "kneesim: no calibrated contact law for %s: calibrating it against the "
                 "deformable insert (first use: one deformable gait cycle on the reference mesh, "
                 "minutes, and about 200 short rigid ones; cached; --no-calibrate runs the law "
                 "as specified instead)\n",
                 what.c_str());
  }
  // scratch folder: in the cache folder when there is one, else the system's temporary folder
  const fs::path cache = models::contact_law_cache_dir();
  const fs::path scratch =
      (cache.empty() ? fs::temp_directory_path() : cache) /
      ("calibrating-" + config.contact_law_resolution.key + "-" + std::to_string(::getpid()));
  ContactCalibrationJob job;
  job.config = models::make_calibration_config(config);  // the reference it is looked up under
  job.out = scratch;
  job.command = "calibration on first use (kneesim " + std::string(config.file.empty() ? "" : config.file.string()) + ")";
  job.plots = false;
  job.quiet = quiet;
  ContactCalibrationReport report;
  try {
    fs::create_directories(scratch);
    report = calibrate_contact_law(job);
  } catch (const std::exception& e) {
    throw InputError("calibrating the contact law for " + what + " failed: " + e.what() +
                     "; run with --no-calibrate (contact.calibration = \"off\") for the law as "
                     "specified, or name a law file (contact.law_file)");
  }
  fs::path file = scratch / "contact_law.toml";
  if (!cache.empty()) {
    const fs::path kept = cache / (report.law.key.key + ".toml");
    try {
      models::write_contact_law_file(kept, report.law);
      file = kept;
    } catch (const std::exception&) {
      // a cache that cannot be written is no cache: the law holds for this process
    }
  }
  std::error_code ec;
  if (file.parent_path() != scratch) fs::remove_all(scratch, ec);
  models::remember_contact_law(report.law, file);
  models::resolve_contact_law(config);
  if (!quiet) {
    std::fprintf(stderr, "kneesim: calibrated K_eff = %.1f MPa (%.3f K); law in %s\n",
                 report.law.foundation_modulus_MPa,
                 report.law.foundation_modulus_MPa / report.law.specified_modulus_MPa,
                 file.c_str());
  }
  return true;
}

nlohmann::json describe_contact_law(const models::Config& c, double modulus_MPa) {
  const models::ContactLawResolution& r = c.contact_law_resolution;
  nlohmann::json j;
  j["law"] = c.contact_law;
  j["foundation_modulus_MPa"] = modulus_MPa;
  j["exponent"] = c.contact_law_exponent;  // n of p = K g^n
  j["specified_modulus_MPa"] =
      engine::foundation_modulus(c.material.elastic_modulus_MPa, c.material.poisson);
  j["source"] = r.source;
  if (!r.file.empty()) j["file"] = r.file;
  if (!r.key.empty()) j["key"] = r.key;
  if (!r.warning.empty()) j["warning"] = r.warning;
  if (!r.note.empty()) j["note"] = r.note;
  if (!r.provenance.empty()) {
    nlohmann::json p;
    for (const auto& [k, v] : r.provenance) {
      char* end = nullptr;
      const double x = std::strtod(v.c_str(), &end);
      if (!v.empty() && end && *end == '\0') {
        p[k] = x;
      } else if (v.size() >= 2 && v.front() == '"' && v.back() == '"') {
        p[k] = v.substr(1, v.size() - 2);
      } else {
        p[k] = v;
      }
    }
    j["provenance"] = p;
  }
  return j;
}

}  // namespace kneesim::run
