#include "analysis/run/material_comparison.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <set>
#include <thread>

#include "analysis/run/run_outputs.h"
#include "engine/errors.h"
#include "engine/io/source_tree.h"
#include "engine/io/toml_file.h"
#include "wear/archard.h"
#include "wear/wear_law.h"

namespace kneesim::run {
namespace {

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

double num(const nlohmann::json& j, const char* key) {
  return j.contains(key) ? j[key].get<double>() : std::nan("");
}

// "1.23", "1.23 (volume jumps by ... between ratios a and b ...)" or "not found (why)"
std::string ratio_text(const BreakEven& b) {
  if (!std::isfinite(b.ratio)) return "not found (" + b.note + ")";
  return fmt("%.3g", b.ratio) + (b.note.empty() ? "" : " (" + b.note + ")");
}

}  // namespace

std::filesystem::path wear_literature_path() {
  return io::source_dir() / "models/wear_literature.toml";
}

std::vector<LiteratureBand> read_wear_literature(const std::filesystem::path& file) {
  const io::TomlDocument doc = io::read_toml_file(file);
  std::map<std::string, LiteratureBand> bands;
  for (const auto& [key, entry] : doc) {
    const auto dot = key.find('.');
    const std::string where = file.string() + ":" + std::to_string(entry.line);
    if (dot == std::string::npos) {
      throw InputError(where + ": '" + key + "' must be a table [name] of one published range");
    }
    LiteratureBand& b = bands[key.substr(0, dot)];
    b.key = key.substr(0, dot);
    const std::string field = key.substr(dot + 1);
    const auto* text = std::get_if<std::string>(&entry.value);
    const auto* number = std::get_if<double>(&entry.value);
    if (field == "ratio_low" || field == "ratio_high") {
      if (!number || !(*number > 0.0) || !std::isfinite(*number)) {
        throw InputError(where + ": key '" + key + "' = " + io::describe(entry.value) +
                         " is not allowed (a positive wear-factor ratio)");
      }
      (field == "ratio_low" ? b.ratio_low : b.ratio_high) = *number;
    } else if (text && field == "material") {
      b.material = *text;
    } else if (text && field == "open_end") {
      if (*text != "" && *text != "low" && *text != "high") {
        throw InputError(where + ": key '" + key + "' = \"" + *text +
                         "\" is not allowed (one of \"\", \"low\", \"high\")");
      }
      b.open_end = *text;
    } else if (text && field == "citation") {
      b.citation = *text;
    } else if (text && field == "conditions") {
      b.conditions = *text;
    } else if (text && field == "reading") {
      b.reading = *text;
    } else {
      throw InputError(where + ": unknown or mistyped key '" + key + "' (allowed: material, "
                       "ratio_low, ratio_high, open_end, citation, conditions, reading)");
    }
  }
  std::vector<LiteratureBand> out;
  for (auto& [name, b] : bands) {
    if (b.material.empty() || b.citation.empty() || !(b.ratio_low > 0.0) ||
        !(b.ratio_high >= b.ratio_low)) {
      throw InputError(file.string() + ": [" + name + "] needs material, citation and "
                       "0 < ratio_low <= ratio_high");
    }
    out.push_back(b);
  }
  return out;
}

std::vector<MaterialBreakEven> calc_break_evens(const std::vector<WearJob>& jobs,
                                                const std::vector<nlohmann::json>& results,
                                                size_t reference,
                                                const BreakEvenSettings& settings) {
  // the law's coefficient (k, or C of the contact-area law) of each material, SI
  const auto coefficient = [](const WearJob& j) {
    return wear::law_coefficient(
        wear::make_wear_law(j.config.wear, j.config.material, j.config.material.friction));
  };
  const double k_ref = coefficient(jobs[reference]);
  const double volume_ref = num(results[reference], "volume_mm3");
  const double depth_ref = num(results[reference], "max_depth_mm");
  // every material's model once, shared by its runs (read-only)
  std::vector<size_t> others;
  for (size_t i = 0; i < jobs.size(); ++i)
    if (i != reference) others.push_back(i);
  std::vector<std::unique_ptr<models::BuiltModel>> built(jobs.size());
  std::vector<MaterialBreakEven> out(others.size());
  // tasks: per material one solve (volume, then depth, sharing their runs) and one run per
  // grid ratio; each task has its own cache, merged afterwards (runs are deterministic)
  struct Task {
    size_t slot;        // index into out
    double grid_ratio;  // 0 for the solve
  };
  std::vector<Task> tasks;
  for (size_t s = 0; s < others.size(); ++s) tasks.push_back({s, 0.0});
  for (size_t s = 0; s < others.size(); ++s)
    for (double r : settings.grid) tasks.push_back({s, r});
  std::vector<std::vector<RatioRun>> task_runs(tasks.size());
  for (size_t s = 0; s < others.size(); ++s) {
    const size_t i = others[s];
    built[i] = std::make_unique<models::BuiltModel>(models::build_model(jobs[i].config));
    MaterialBreakEven& m = out[s];
    m.material = jobs[i].config.material.name;
    m.own_ratio = coefficient(jobs[i]) / k_ref;
    m.own_independent = jobs[i].config.material.wear_factor_independent;
  }
  std::vector<std::exception_ptr> errors(tasks.size());
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t t = next++; t < tasks.size(); t = next++) {
      try {
        const size_t s = tasks[t].slot, i = others[s];
        RatioRuns runs(*built[i], make_wear_options(jobs[i], *built[i]), k_ref);
        if (tasks[t].grid_ratio > 0.0) {
          runs.at(tasks[t].grid_ratio);
        } else {
          // the comparison's own run is the run at the material's own ratio
          RatioRun own;
          own.ratio = out[s].own_ratio;
          own.complete = results[i].value("status", "") == "complete";
          own.volume_mm3 = num(results[i], "volume_mm3");
          own.max_depth_mm = num(results[i], "max_depth_mm");
          own.cycles = num(results[i], "cycles");
          runs.add(own);
          out[s].volume = solve_break_even(runs, BreakEvenTarget::kVolume, volume_ref, own.ratio);
          const double start = std::isfinite(out[s].volume.ratio) ? out[s].volume.ratio : own.ratio;
          out[s].max_depth = solve_break_even(runs, BreakEvenTarget::kMaxDepth, depth_ref, start);
        }
        task_runs[t] = runs.all();
      } catch (...) {
        errors[t] = std::current_exception();
      }
    }
  };
  int workers = settings.workers > 0 ? settings.workers
                                     : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  workers = std::min<int>(workers, static_cast<int>(tasks.size()));
  std::vector<std::thread> pool;
  for (int w = 0; w < workers; ++w) pool.emplace_back(work);
  for (auto& th : pool) th.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  for (size_t t = 0; t < tasks.size(); ++t) {
    std::vector<RatioRun>& all = out[tasks[t].slot].runs;
    for (const RatioRun& r : task_runs[t]) {
      if (std::none_of(all.begin(), all.end(), [&r](const RatioRun& q) { return q.ratio == r.ratio; }))
        all.push_back(r);
    }
  }
  for (MaterialBreakEven& m : out) {
    std::sort(m.runs.begin(), m.runs.end(),
              [](const RatioRun& a, const RatioRun& b) { return a.ratio < b.ratio; });
  }
  return out;
}

std::string independence_statement(const std::vector<WearJob>& jobs,
                                   const std::vector<std::string>& names) {
  std::string list;
  for (size_t i = 0; i < jobs.size(); ++i) {
    const models::MaterialConfig& m = jobs[i].config.material;
    if (m.wear_factor_independent) continue;
    list += "- " + names[i] + ": " + m.wear_factor_source + "\n";
  }
  if (list.empty()) return "";
  return "**Not a prediction of wear.** These wear factors are not independent of the "
         "comparisons kneesim makes, so the volumes, masses and depths they give, and the "
         "ranking by them, are not kneesim predictions (the break-even ratios below are):\n\n" +
         list + "\n";
}

std::string make_comparison_markdown(const std::vector<WearJob>& jobs,
                                     const std::vector<std::string>& names,
                                     const std::vector<nlohmann::json>& results,
                                     const std::vector<MaterialBreakEven>& break_evens,
                                     const std::string& reference,
                                     const std::vector<LiteratureBand>& bands) {
  const bool solid = results.front().contains("von_mises_max_surface_MPa");
  const WearPotentialUnit unit = wear_potential_unit(jobs.front().config.wear.law);
  const std::string potential = "wear_potential_" + unit.suffix;
  const std::string potential_run = "wear_potential_run_" + unit.suffix;
  std::string md =
      "## Contact mechanics and kinematics (independent of the wear factor)\n\n"
      "Pristine insert, one settled gait cycle; the wear potential is what the wear law "
      "multiplies by its coefficient (volume = k x potential), per cycle on the pristine "
      "insert and summed over the run with its geometry updates.\n\n"
      "| material | peak pressure (MPa) | mean peak pressure (MPa) | stance mean pressure (MPa) "
      "| contact area (mm²) | sliding distance (mm/cycle) | cross-shear ratio | wear potential "
      "(" + unit.text + "/cycle) | wear potential over the run (" + unit.text + ") | AP ROM (mm) "
      "| IE ROM (deg) |";
  md += solid ? " von Mises max surface / subsurface (MPa) | plastic strain max surface / "
                "subsurface |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n"
              : "\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < results.size(); ++i) {
    const auto& r = results[i];
    md += "| " + names[i] + " | " + fmt("%.1f", num(r, "peak_pressure_MPa")) + " | " +
          fmt("%.1f", num(r, "mean_peak_pressure_MPa")) + " | " +
          fmt("%.1f", num(r, "stance_mean_pressure_MPa")) + " | " +
          fmt("%.1f", num(r, "contact_area_mm2")) + " | " +
          fmt("%.1f", num(r, "sliding_distance_mm")) + " | " +
          fmt("%.3f", num(r, "cross_shear_ratio")) + " | " +
          fmt("%.4g", num(r, potential.c_str())) + " | " +
          fmt("%.4g", num(r, potential_run.c_str())) + " | " + fmt("%.2f", num(r, "ap_rom_mm")) +
          " | " + fmt("%.2f", num(r, "ie_rom_deg")) + " |";
    if (solid) {
      md += " " + fmt("%.1f", num(r, "von_mises_max_surface_MPa")) + " / " +
            fmt("%.1f", num(r, "von_mises_max_subsurface_MPa")) + " | " +
            fmt("%.4f", num(r, "plastic_strain_max_surface")) + " / " +
            fmt("%.4f", num(r, "plastic_strain_max_subsurface")) + " |";
    }
    md += "\n";
  }
  md += "\n## Wear (depends on the wear factor)\n\n"
        "| material | wear factor (mm³/(N mm)) | independent | volume (mm³) | mass (mg) | "
        "max depth (mm) | wear rate (mm³/Mc) |\n|---|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < results.size(); ++i) {
    const auto& r = results[i];
    const models::MaterialConfig& m = jobs[i].config.material;
    md += "| " + names[i] + " | " + fmt("%.4g", m.wear_factor_mm3_per_Nmm) + " | " +
          (m.wear_factor_independent ? "yes" : "**no**") + " | " +
          fmt("%.1f", num(r, "volume_mm3")) + " | " + fmt("%.1f", num(r, "mass_mg")) + " | " +
          fmt("%.3f", num(r, "max_depth_mm")) + " | " +
          fmt("%.2f", num(r, "wear_rate_mm3_per_Mc")) + " |\n";
  }
  md += "\n" + independence_statement(jobs, names);
  if (break_evens.empty()) return md;
  md += "\n## Break-even wear-factor ratio to " + reference +
        "\n\nThe ratio k / k_" + reference + " at which the material's volume (or maximum "
        "depth) at the end of the run equals " + reference + "'s on this implant, rig and gait, "
        "solved on the whole run (wear is not linear in k once the geometry updates). A "
        "material whose real factor ratio is below its break-even wears less than " +
        reference + ". Published ranges are what the sources' readable text states "
        "(models/wear_literature.toml).\n\n"
        "| material | ratio for equal volume | ratio for equal max depth | its own factor's "
        "ratio | published ranges |\n|---|---|---|---|---|\n";
  for (const MaterialBreakEven& b : break_evens) {
    std::string published;
    for (const LiteratureBand& l : bands) {
      if (l.material != b.material) continue;
      const std::string lo = l.open_end == "low" ? "" : fmt("%.3g", l.ratio_low);
      const std::string hi = l.open_end == "high" ? "" : fmt("%.3g", l.ratio_high);
      published += (published.empty() ? "" : "; ") +
                   (lo.empty() ? "≤ " + hi : hi.empty() ? "≥ " + lo : lo + "-" + hi) + " (" +
                   l.citation + ")";
    }
    md += "| " + b.material + " | " + ratio_text(b.volume) + " | " + ratio_text(b.max_depth) +
          " | " + fmt("%.3g", b.own_ratio) +
          (b.own_independent ? "" : " (not independent: the materials study's implied ratio)") +
          " | " + (published.empty() ? "none read" : published) + " |\n";
  }
  return md;
}

nlohmann::json break_even_json(const std::vector<MaterialBreakEven>& break_evens,
                               const std::string& reference, const nlohmann::json& reference_result,
                               const std::vector<LiteratureBand>& bands) {
  nlohmann::json j;
  j["reference"] = reference;
  j["reference_volume_mm3"] = reference_result["volume_mm3"];
  j["reference_max_depth_mm"] = reference_result["max_depth_mm"];
  j["cycles"] = reference_result["cycles"];
  auto number_or_null = [](double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
  };
  auto ratio_or_null = [&number_or_null](const BreakEven& b) { return number_or_null(b.ratio); };
  // the bracket of a solve: its ends and their results (null where not known), whether the
  // result jumps across the goal inside it and by how much
  auto add_bracket = [&number_or_null](nlohmann::json& m, const std::string& prefix,
                                       const BreakEven& b) {
    m[prefix + "_converged"] = b.converged;
    m[prefix + "_ratio_low"] = b.lo > 0.0 ? nlohmann::json(b.lo) : nlohmann::json(nullptr);
    m[prefix + "_ratio_high"] = number_or_null(b.hi);
    m[prefix + "_result_low"] = b.lo > 0.0 ? nlohmann::json(b.result_lo) : nlohmann::json(nullptr);
    m[prefix + "_result_high"] = number_or_null(b.result_hi);
    m[prefix + "_jump_pct"] = number_or_null(jump_percent(b));
  };
  for (const MaterialBreakEven& b : break_evens) {
    j["order"].push_back(b.material);
    nlohmann::json m;
    m["own_ratio"] = b.own_ratio;
    m["own_factor_independent"] = b.own_independent;
    m["volume_ratio"] = ratio_or_null(b.volume);
    m["volume_runs"] = b.volume.runs;
    m["volume_note"] = b.volume.note;
    m["max_depth_ratio"] = ratio_or_null(b.max_depth);
    m["max_depth_runs"] = b.max_depth.runs;
    m["max_depth_note"] = b.max_depth.note;
    add_bracket(m, "volume", b.volume);
    add_bracket(m, "max_depth", b.max_depth);
    for (const RatioRun& r : b.runs) {
      m["runs"].push_back({{"ratio", r.ratio},
                           {"complete", r.complete},
                           {"volume_mm3", r.volume_mm3},
                           {"max_depth_mm", r.max_depth_mm},
                           {"cycles", r.cycles},
                           {"failure", r.failure}});
    }
    j["materials"][b.material] = m;
  }
  for (const LiteratureBand& l : bands) {
    j["literature"].push_back({{"key", l.key},
                               {"material", l.material},
                               {"ratio_low", l.ratio_low},
                               {"ratio_high", l.ratio_high},
                               {"open_end", l.open_end},
                               {"citation", l.citation},
                               {"conditions", l.conditions},
                               {"reading", l.reading}});
  }
  return j;
}

}  // namespace kneesim::run
