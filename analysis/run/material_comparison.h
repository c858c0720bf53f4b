// What `kneesim compare` can say about insert materials without borrowing the answer: per
// material, the figures that do not depend on the wear factor (contact pressure, area, sliding,
// cross-shear, stresses, the wear potential), whether its wear factor is independent of the
// comparisons kneesim makes (models/materials.toml), and the break-even wear-factor ratio to a
// reference material (analysis/run/break_even.h), set beside the published ratios
// (models/wear_literature.toml) and the ratio the material's own factor implies.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/run/break_even.h"
#include "analysis/run/wear_job.h"

namespace kneesim::run {

// a published range of the wear-factor ratio k_material / k_UHMWPE (models/wear_literature.toml)
struct LiteratureBand {
  std::string key;          // the table's name
  std::string material;
  double ratio_low = 0.0, ratio_high = 0.0;  // [-]
  std::string open_end;     // "", "low" or "high": the bound the source does not state
  std::string citation, conditions, reading;
};

// reads the bands; throws InputError naming file, key, value and range
std::vector<LiteratureBand> read_wear_literature(const std::filesystem::path& file);
std::filesystem::path wear_literature_path();  // the shipped models/wear_literature.toml

struct MaterialBreakEven {
  std::string material;
  double own_ratio = 0.0;        // the material's own factor / the reference's [-]
  bool own_independent = true;   // whether the material's own factor is independent
  BreakEven volume, max_depth;
  std::vector<RatioRun> runs;    // every run made or known, by ratio (the plot's points)
};

struct BreakEvenSettings {
  // ratios run for the plot's curve besides the solves' runs
  std::vector<double> grid{0.01, 0.1, 1.0, 10.0, 100.0};
  int workers = 0;  // threads (0: all cores)
};

// the break-even of every material of `jobs` except the reference (index `reference`), from
// the comparison's finished `results` (summary.json of each job)
std::vector<MaterialBreakEven> calc_break_evens(const std::vector<WearJob>& jobs,
                                                const std::vector<nlohmann::json>& results,
                                                size_t reference,
                                                const BreakEvenSettings& settings);

// the comparison's Markdown: the factor-free table, the wear table (with the independence
// statement when any factor is not independent), and the break-even table with the bands
std::string make_comparison_markdown(const std::vector<WearJob>& jobs,
                                     const std::vector<std::string>& names,
                                     const std::vector<nlohmann::json>& results,
                                     const std::vector<MaterialBreakEven>& break_evens,
                                     const std::string& reference,
                                     const std::vector<LiteratureBand>& bands);

// the one-paragraph statement about factors that are not independent ("" when all are)
std::string independence_statement(const std::vector<WearJob>& jobs,
                                   const std::vector<std::string>& names);

// comparison.json's "break_even" object (also what the plot reads)
nlohmann::json break_even_json(const std::vector<MaterialBreakEven>& break_evens,
                               const std::string& reference, const nlohmann::json& reference_result,
                               const std::vector<LiteratureBand>& bands);

}  // namespace kneesim::run
