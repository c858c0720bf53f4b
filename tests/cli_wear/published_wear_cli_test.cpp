// `kneesim diagnose published-wear` end to end (issue 25, items 4-5), with stated references:
//  - each law's prediction of a condition is the wear rate `kneesim run` reports for the same
//    law and inputs (cycle_wear_rate_mm3_per_Mc of the last of 2 cycles: the diagnosis' forward
//    model is the run's, so they agree to the rounding of spreading element depths to
//    vertices, 1e-9 relative);
//  - a calibrated law reproduces the measured mean of its calibration condition (one scale
//    fitted, closed form), and its within-study ratios equal the uncalibrated ones (the scale
//    cancels);
//  - the trivial predictor is the calibration condition's measured mean everywhere;
//  - bad input: an SD that is not positive, n < 1, a condition missing from the config: exit 2
//    and one line naming the file, row, column or condition, the value and what is allowed.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "tests/cli_wear/cli_helpers.h"

using namespace kneesim;
using namespace kneesim::test;

namespace {

std::string source_dir() {
  const char* s = std::getenv("KNEESIM_SOURCE_DIR");
  return s ? s : "";
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

// a two-condition study in the form of analysis/diagnosis/data/*.csv
void write_study(const fs::path& csv, const std::string& low_sd = "2",
                 const std::string& high_n = "6") {
  spit(csv, "# test study\ncondition,cycles,mean,sd,n,units,note\n"
            "low,3000000,7.7," + low_sd + ",6,mm3_per_Mc,first\n"
            "high,3000000,41,14," + high_n + ",mm3_per_Mc,second\n");
}

// the displacement rig at two AP/IE amplitudes (as models/examples/barnett2001.toml)
void write_config(const fs::path& toml, bool with_high = true) {
  std::string text = "[rig]\npreset = \"displacement\"\n\n[conditions.low]\n"
                     "set = [\"gait.ap_displacement_scale=1.0\", \"gait.ie_rotation_scale=0.8\"]\n";
  if (with_high) {
    text += "\n[conditions.high]\nset = [\"gait.ap_displacement_scale=2.0\", "
            "\"gait.ie_rotation_scale=1.6\"]\n";
  }
  spit(toml, text);
}

}  // namespace

TEST_CASE("diagnose published-wear: predictions equal kneesim run's wear rate; calibration") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path csv = tmp.path / "study_wear.csv", toml = tmp.path / "study.toml";
  write_study(csv);
  write_config(toml);
  const fs::path out = tmp.path / "pub";
  const Result r = run_kneesim({"diagnose", "published-wear", "--study",
                                csv.string() + "=" + toml.string(), "--set",
                                "implant.edge_length_mm=2", "--no-plots", "--out", out.string()},
                               tmp.path, "pub");
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const auto s = nlohmann::json::parse(slurp(out / "summary.json"));
  REQUIRE(s["conditions"].size() == 2);
  CHECK(s["calibration"]["condition"] == "low");
  const auto& low = s["conditions"][0];
  const auto& high = s["conditions"][1];
  CHECK(low["held_out"] == false);
  CHECK(high["held_out"] == true);
  for (const auto& law : s["laws"]) {
    const std::string name = law["name"];
    CAPTURE(name);
    // calibrated on low: reproduces its mean; the ratio is the uncalibrated one
    CHECK(rel(low["calibrated_" + name].get<double>(), 7.7) < 1e-12);
    const double ratio = s["ratios"][0][name].get<double>();
    CHECK(rel(high["calibrated_" + name].get<double>() / 7.7, ratio) < 1e-12);
    if (law["absolute"].get<bool>()) {
      CHECK(rel(high["predicted_" + name].get<double>() /
                    low["predicted_" + name].get<double>(), ratio) < 1e-12);
    }
  }
  CHECK(low["trivial"].get<double>() == 7.7);
  CHECK(high["trivial"].get<double>() == 7.7);
  CHECK(s["ratios"][0]["measured"].get<double>() == doctest::Approx(41.0 / 7.7));
  CHECK(fs::exists(out / "report.md"));
  CHECK(fs::exists(out / "published_wear.csv"));
  CHECK(!fs::exists(out / "published_wear.png"));

  // the same conditions through kneesim run, law by law (the diagnosis' parameters from its
  // summary): the cycle wear rate is the diagnosis' prediction
  for (const auto& law : s["laws"]) {
    if (!law["absolute"].get<bool>()) continue;
    const std::string name = law["name"];
    for (const auto& [cond, ap, ie] : {std::tuple{"low", "1.0", "0.8"},
                                       std::tuple{"high", "2.0", "1.6"}}) {
      CAPTURE(name);
      CAPTURE(cond);
      std::vector<std::string> args = {"run", toml.string(), "--cycles", "2",
                                       "--set", "implant.edge_length_mm=2", "--set",
                                       std::string("gait.ap_displacement_scale=") + ap, "--set",
                                       std::string("gait.ie_rotation_scale=") + ie, "--no-plots",
                                       "--quiet", "--out", (tmp.path / "run").string()};
      for (const auto& [key, value] : law["overrides"].items()) {
        args.push_back("--set");
        args.push_back(key + "=" + value.get<std::string>());
      }
      const Result rr = run_kneesim(args, tmp.path, "run");
      REQUIRE_MESSAGE(rr.exit_code == 0, rr.err);
      const auto rs = nlohmann::json::parse(slurp(tmp.path / "run" / "summary.json"));
      const auto& c = std::string(cond) == "low" ? low : high;
      CHECK(rs["wear_law"] == name);
      CHECK(rel(rs["cycle_wear_rate_mm3_per_Mc"].get<double>(),
                c["predicted_" + name].get<double>()) < 1e-9);
    }
  }
}

TEST_CASE("diagnose published-wear: bad input exits 2 with one line naming the value") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path toml = tmp.path / "study.toml";
  write_config(toml);
  const auto refused = [&](const fs::path& csv, const fs::path& config,
                           const std::vector<std::string>& fragments) {
    const Result r = run_kneesim({"diagnose", "published-wear", "--study",
                                  csv.string() + "=" + config.string(), "--no-plots", "--out",
                                  (tmp.path / "out").string()},
                                 tmp.path, "bad");
    CAPTURE(r.err);
    CHECK(r.exit_code == 2);
    CHECK(count_lines(r.err) == 1);
    for (const auto& f : fragments) CHECK(r.err.find(f) != std::string::npos);
  };
  const fs::path zero_sd = tmp.path / "zero_sd.csv";
  write_study(zero_sd, "0");
  refused(zero_sd, toml, {"zero_sd.csv", "column sd", "'0'", "positive SD"});
  const fs::path neg_sd = tmp.path / "neg_sd.csv";
  write_study(neg_sd, "-2");
  refused(neg_sd, toml, {"neg_sd.csv", "column sd", "'-2'"});
  const fs::path no_n = tmp.path / "no_n.csv";
  write_study(no_n, "2", "0");
  refused(no_n, toml, {"no_n.csv", "column n", "'0'", ">= 1"});
  const fs::path ok = tmp.path / "ok.csv";
  write_study(ok);
  const fs::path low_only = tmp.path / "low_only.toml";
  write_config(low_only, false);
  refused(ok, low_only, {"ok.csv", "'high'", "not a condition of", "low_only.toml", "low"});
}
