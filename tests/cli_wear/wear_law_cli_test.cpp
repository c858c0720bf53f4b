// Every wear law end to end through `kneesim wear`, `kneesim compare` and `kneesim study --wear`
// (issue 25): the same law, parameters and inputs give the identical volume and depth in wear
// and compare (compare runs each material through the same library call as wear: any
// difference would be a law not reaching it) and a study trial equals the wear run of its
// inputs; a law that does not exist, a parameter the law does not have, one out of its range
// and creep with a non-positive time constant are refused, on the command line and in a config
// file, with exit 2 and one line naming the key (and the file).
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "tests/cli_wear/cli_helpers.h"

using namespace kneesim;
using namespace kneesim::test;

namespace {

struct LawCase {
  const char* law;
  std::vector<std::string> params;  // --law-param
  std::vector<std::string> sets;    // extra --set
};

std::vector<std::string> with(std::vector<std::string> a, const LawCase& c) {
  a.push_back("--wear-law");
  a.push_back(c.law);
  for (const auto& p : c.params) {
    a.push_back("--law-param");
    a.push_back(p);
  }
  for (const auto& s : c.sets) {
    a.push_back("--set");
    a.push_back(s);
  }
  return a;
}

}  // namespace

TEST_CASE("every wear law: kneesim wear and kneesim compare give identical results") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const std::vector<LawCase> cases = {
      {"archard", {}, {}},
      {"pressure_dependent_wear", {"alpha=0.5", "p_ref_MPa=10"}, {}},
      {"cross_shear", {"cross_shear_gain=5.41"}, {}},
      {"contact_area", {"cross_shear_gain=5.41"}, {"material.area_wear_coefficient=2e-9"}},
      {"running_in", {"running_in_excess=1", "running_in_cycles=1000"}, {}},
      {"incubation", {"incubation_cycles=1000"}, {}},
      {"material_pressure", {}, {}},
      {"cross_shear", {"beta=5.41"}, {"wear.creep=true", "wear.creep_time_s=2000"}},
  };
  double archard_volume = 0.0;
  for (size_t i = 0; i < cases.size(); ++i) {
    const LawCase& c = cases[i];
    const std::string law = c.law;
    CAPTURE(law);
    const fs::path w = tmp.path / ("wear" + std::to_string(i));
    const fs::path cmp = tmp.path / ("cmp" + std::to_string(i));
    const Result rw = run_kneesim(with(wear_args(w, {"--no-plots", "--no-depth-maps"}, "1000", "2000"), c),
                                  tmp.path, "w" + std::to_string(i));
    REQUIRE_MESSAGE(rw.exit_code == 0, rw.err);
    const Result rc = run_kneesim(
        with({"compare", "--materials", "uhmwpe", "--cycles", "2000", "--update-every", "1000",
              "--set", "implant.edge_length_mm=2", "--quiet", "--no-plots", "--out",
              cmp.string()},
             c),
        tmp.path, "c" + std::to_string(i));
    REQUIRE_MESSAGE(rc.exit_code == 0, rc.err);
    const auto sw = nlohmann::json::parse(slurp(w / "summary.json"));
    const auto sc = nlohmann::json::parse(slurp(cmp / "uhmwpe" / "summary.json"));
    CHECK(sw["wear_law"] == c.law);
    CHECK(sc["wear_law"] == c.law);
    CHECK(sw["volume_mm3"].get<double>() > 0.0);
    CHECK(sw["volume_mm3"].get<double>() == sc["volume_mm3"].get<double>());
    CHECK(sw["max_depth_mm"].get<double>() == sc["max_depth_mm"].get<double>());
    CHECK(sw["max_penetration_mm"].get<double>() == sc["max_penetration_mm"].get<double>());
    if (i == 0) archard_volume = sw["volume_mm3"].get<double>();
    if (i == 2) CHECK(sw["volume_mm3"].get<double>() > archard_volume);  // f(CS) >= 1
    if (i == cases.size() - 1) {
      // creep adds penetration, never volume: the same law without creep is case 2
      const auto s2 = nlohmann::json::parse(slurp(tmp.path / "wear2" / "summary.json"));
      CHECK(sw["volume_mm3"].get<double>() == s2["volume_mm3"].get<double>());
      CHECK(sw["max_creep_depth_mm"].get<double>() > 0.0);
      CHECK(sw["max_penetration_mm"].get<double>() > sw["max_depth_mm"].get<double>());
      CHECK(s2["max_penetration_mm"].get<double>() == s2["max_depth_mm"].get<double>());
    }
  }
}

TEST_CASE("bad wear-law input on the command line: exit 2, one line naming the key") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const auto refused = [&](const std::vector<std::string>& args, const std::string& fragment) {
    const Result r = run_kneesim(args, tmp.path, "bad");
    CAPTURE(r.err);
    CHECK(r.exit_code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.find(fragment) != std::string::npos);
  };
  refused({"wear", "--wear-law", "magic", "--out", (tmp.path / "a").string()}, "wear.law");
  refused({"wear", "--law-param", "beta=3", "--out", (tmp.path / "b").string()},
          "wear.cross_shear_gain");
  refused({"compare", "--wear-law", "cross_shear", "--law-param", "beta=-1", "--out",
           (tmp.path / "c").string()},
          "[0, 1000]");
  refused({"wear", "--set", "wear.creep=true", "--set", "wear.creep_time_s=0", "--out",
           (tmp.path / "d").string()},
          "wear.creep_time_s");
  refused({"study", "--wear", "--wear-law", "contact_area", "--out", (tmp.path / "e").string()},
          "area_wear_coefficient");
  // run refuses the law before building the model and before clearing the folder's outputs of
  // an earlier run (it cleared them and printed its banner first)
  fs::create_directories(tmp.path / "f");
  spit(tmp.path / "f" / "summary.json", "{}");
  refused({"run", "--set", "wear.law=\"contact_area\"", "--cycles", "1", "--no-plots", "--out",
           (tmp.path / "f").string()},
          "area_wear_coefficient");
  CHECK(fs::exists(tmp.path / "f" / "summary.json"));
}

TEST_CASE("bad wear-law keys in a config file: exit 2, one line naming file, key, value, range") {
  // Every command that reads a config (run, wear, compare, study --wear, diagnose knee-wear)
  // refuses, before simulating: a law that does not exist, a parameter the law does not have,
  // a parameter outside its range, and creep with a non-positive time constant (0 and
  // negative). The message names the file and line, the key, the value and what is allowed.
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  spit(tmp.path / "measured.csv", "condition,cycles,volume_mm3\niso,1000000,10\n");
  struct BadFile {
    const char* name;
    const char* toml;
    std::vector<std::string> fragments;
  };
  const std::vector<BadFile> files = {
      {"no_law.toml", "[wear]\nlaw = \"magic\"\n",
       {"no_law.toml:2", "'wear.law'", "\"magic\"", "\"archard\"", "\"cross_shear\"",
        "\"contact_area\"", "\"incubation\""}},
      {"foreign_param.toml", "[wear]\nlaw = \"running_in\"\ncross_shear_gain = 2.0\n",
       {"foreign_param.toml:3", "'wear.cross_shear_gain'", "not a parameter", "\"running_in\"",
        "wear.running_in_excess, wear.running_in_cycles"}},
      {"gain_range.toml", "[wear]\nlaw = \"cross_shear\"\ncross_shear_gain = -1.0\n",
       {"gain_range.toml:3", "'wear.cross_shear_gain'", "= -1", "[0, 1000]"}},
      {"exponent_range.toml", "[wear]\nlaw = \"pressure_dependent_wear\"\npressure_exponent = 7\n",
       {"exponent_range.toml:3", "'wear.pressure_exponent'", "= 7", "[-3, 4]"}},
      {"creep_zero.toml", "[wear]\nlaw = \"cross_shear\"\ncreep = true\ncreep_time_s = 0.0\n",
       {"creep_zero.toml:4", "'wear.creep_time_s'", "= 0 ", "[0.001, 1e+12]"}},
      {"creep_negative.toml", "[wear]\ncreep = true\ncreep_time_s = -5.0\n",
       {"creep_negative.toml:3", "'wear.creep_time_s'", "= -5", "[0.001, 1e+12]"}},
  };
  for (const BadFile& f : files) {
    const fs::path config = tmp.path / f.name;
    spit(config, f.toml);
    const std::vector<std::vector<std::string>> commands = {
        {"run", config.string(), "--no-plots"},
        {"wear", config.string(), "--no-plots"},
        {"compare", config.string(), "--no-plots"},
        {"study", config.string(), "--wear"},
        {"diagnose", "knee-wear", "--config", config.string(), "--measured",
         (tmp.path / "measured.csv").string()},
    };
    for (const auto& command : commands) {
      std::vector<std::string> args = command;
      args.push_back("--out");
      args.push_back((tmp.path / "out").string());
      const Result r = run_kneesim(args, tmp.path, "bad");
      CAPTURE(f.name);
      CAPTURE(command[0]);
      CAPTURE(r.err);
      CHECK(r.exit_code == 2);
      CHECK(count_lines(r.err) == 1);
      for (const auto& fragment : f.fragments) CHECK(r.err.find(fragment) != std::string::npos);
      CHECK(!fs::exists(tmp.path / "out" / "summary.json"));
    }
  }
}

TEST_CASE("every wear law: a kneesim study --wear trial equals kneesim wear of its inputs") {
  // Two LHS trials per law (Pal 2008's 13 variables; the study's least), 2000 cycles in 1
  // update; the first trial is checked. The reference is `kneesim wear` with the trial's
  // inputs as trials.csv prints them (10 significant digits, so agreement to 1e-6 relative, as
  // tests/cli_study's Archard case) and the same law: the trial is that wear run.
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const std::vector<LawCase> cases = {
      {"archard", {}, {}},
      {"pressure_dependent_wear", {"alpha=0.5"}, {}},
      {"cross_shear", {"cross_shear_gain=5.41"}, {}},
      {"contact_area", {"cross_shear_gain=5.41"}, {"material.area_wear_coefficient=2e-9"}},
      {"running_in", {"running_in_excess=1", "running_in_cycles=1000"}, {}},
      {"incubation", {"incubation_cycles=1000"}, {}},
      {"material_pressure", {}, {}},
      // creep on top of a law (wear.creep): the trial's wear depth and mass are still the
      // wear run's (creep is penetration, reported apart)
      {"cross_shear", {"cross_shear_gain=5.41"}, {"wear.creep=true"}},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const LawCase& c = cases[i];
    const std::string law = c.law;
    CAPTURE(law);
    CAPTURE(c.sets.size());
    const fs::path out = tmp.path / ("study" + std::to_string(i));
    const Result r = run_kneesim(
        with({"study", "--method", "lhs", "--trials", "2", "--seed", "5", "--set",
              "implant.edge_length_mm=2", "--threads", "1", "--quiet", "--out", out.string(),
              "--wear", "--wear-cycles", "2000", "--wear-updates", "1"},
             c),
        tmp.path, "s" + std::to_string(i));
    REQUIRE_MESSAGE(r.exit_code == 0, r.err);
    const std::vector<std::string> rows = split(slurp(out / "trials.csv"), '\n');
    REQUIRE(rows.size() >= 2);
    const std::vector<std::string> head = split(rows[0], ',');
    const std::vector<std::string> cells = split(rows[1], ',');
    REQUIRE(cells.back().rfind("ok", 0) == 0);
    const auto col = [&head](const std::string& name) {
      for (size_t k = 0; k < head.size(); ++k)
        if (head[k] == name) return k;
      FAIL("no column " << name);
      return size_t{0};
    };
    std::vector<std::string> args =
        with(wear_args(tmp.path / ("single" + std::to_string(i)), {"--no-plots",
                                                                    "--no-depth-maps"},
                       "2000", "2000"),
             c);
    for (size_t k = 2; k < col("ap_rom_mm"); ++k) {  // the trial's inputs
      args.push_back("--set");
      args.push_back(head[k] + "=" + cells[k]);
    }
    args.push_back("--allow-any-wear-factor");
    const Result w = run_kneesim(args, tmp.path, "w" + std::to_string(i));
    REQUIRE_MESSAGE(w.exit_code == 0, w.err);
    const auto ws =
        nlohmann::json::parse(slurp(tmp.path / ("single" + std::to_string(i)) / "summary.json"));
    CHECK(ws["wear_law"] == c.law);
    if (!c.sets.empty() && c.sets[0] == "wear.creep=true") {  // the creep case did creep
      CHECK(ws["creep"] == true);
      CHECK(ws["max_penetration_mm"].get<double>() > ws["max_depth_mm"].get<double>());
    }
    const double lin = std::stod(cells[col("max_linear_wear_mm")]);
    const double grav = std::stod(cells[col("gravimetric_wear_mg")]);
    CHECK(lin > 0.0);
    CHECK(ws["max_depth_mm"].get<double>() == doctest::Approx(lin).epsilon(1e-6).scale(0));
    CHECK(ws["mass_mg"].get<double>() == doctest::Approx(grav).epsilon(1e-6).scale(0));
  }
}
