// Hidden-effect tests of the forces diagnosis (issue 16): synthetic instrumented-knee data made
// by the forward simulator itself (a direct simulation at the hidden value, not the grid the
// diagnosis interpolates) with a known load-line shift or stance VV moment, or none, plus
// measurement noise of three kinds (white; AR(1)-correlated drift; proportional to the load);
// the diagnosis must name the hidden effect every time and never name one when there is none.
// The built-in implant at 2 mm edges keeps it fast; the loads are the shipped ISO 14243-1-
// shaped axial force and flexion (approximate), two cycles, the second 7 % lighter.
//
// Also: `kneesim diagnose forces` end to end on the same kind of data (outputs and keys) and
// its bad-input contract.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "engine/io/source_tree.h"
#include "analysis/diagnosis/forces_diagnosis.h"
#include "loads/iso14243/waveform.h"
#include "models/config.h"
#include "tests/cli_wear/cli_helpers.h"
#include "tests/loads/input_error.h"

using namespace kneesim;
using namespace kneesim::diagnosis;
namespace fs = std::filesystem;

namespace {

constexpr double kRate = 100.0;      // samples per second
constexpr double kStart = 0.10;      // heel strike of cycle 1 [s]
constexpr double kPeriod = 1.0;      // [s]
constexpr double kEnd = 2.25;        // end of the record [s]

// the synthetic table: time_s, total_N, flexion_deg, medial_N (the medial column filled with
// the baseline's share of 0.6 here; the tests replace it)
std::string loads_table() {
  const auto w = loads::load_waveform(kneesim::io::source_dir().string() +
                                       "/loads/iso14243/iso14243_1_approx.csv");
  const int ax = w.channel("axial_force_N"), fe = w.channel("flexion_deg");
  std::ostringstream o;
  o << "time_s,total_N,flexion_deg,medial_N\n";
  for (int i = 0; i / kRate <= kEnd; ++i) {
    const double t = i / kRate;
    double phase = std::fmod((t - kStart) / kPeriod + 10.0, 1.0) * 100.0;
    const bool second = t >= kStart + kPeriod;
    const double total = w.value(ax, phase) * (second ? 0.93 : 1.0);
    const double flex = w.value(fe, phase) + (second ? 2.0 : 0.0) * std::sin(M_PI * phase / 100.0);
    o << t << "," << total << "," << flex << "," << 0.6 * total << "\n";
  }
  return o.str();
}

const char* kConfig = R"toml(
[implant]
edge_length_mm = 2.0
[gait.measured]
file = "synthetic.csv"
window = [0.10, 1.10]
channels = ["axial_force_N = total_N", "flexion_deg = flexion_deg"]
compare = ["medial_force_N = medial_N"]
)toml";

enum class Noise { white, drift, proportional };
const char* noise_name(Noise n) {
  return n == Noise::white ? "white 30 N" : n == Noise::drift ? "AR(1) drift 40 N" : "3 % of load";
}

// noise of the medial force per row (rows are in time order within each cycle)
std::vector<double> make_noise(Noise kind, const ForcesMeasured& m, std::mt19937_64& rng) {
  std::normal_distribution<double> z(0.0, 1.0);
  std::vector<double> e(m.data.rows.size());
  double ar = 0.0;
  for (size_t i = 0; i < e.size(); ++i) {
    switch (kind) {
      case Noise::white: e[i] = 30.0 * z(rng); break;
      case Noise::drift:  // correlation 0.9 per sample (time constant 0.1 s), sd 40 N
        ar = 0.9 * ar + std::sqrt(1.0 - 0.81) * z(rng);
        e[i] = 40.0 * ar;
        break;
      case Noise::proportional: e[i] = 0.03 * m.total_N[i] * z(rng); break;
    }
  }
  return e;
}

struct Fixture {
  test::TempDir tmp;
  models::Config config;
  ForcesMeasured measured;
  std::shared_ptr<ForcesSimulator> sim;
  Fixture() {
    tmp.write("synthetic.csv", loads_table());
    config = models::load_config(tmp.write("synthetic.toml", kConfig), {});
    measured = read_forces_measured(config, "");
    sim = std::make_shared<ForcesSimulator>(config, measured.cycles);
    sim->set_threads(2);
  }
  // the measured medial force of every row: a direct simulation with the hidden effect splits
  // the measured total (the instrumented implant's total is the sum of its compartment forces,
  // as in forces_synthetic.cpp). The simulated axial contact force itself is not the table's
  // total: the femoral carriage's inertia and damping make it lag and ring around the applied
  // load (RMS gap printed below), an error no effect of the library models (with the
  // calibrated UHMWPE law it alone moves the fitted vv_moment of the -6 mm trial by about 18 %).
  ForcesMeasured synthetic(Effect truth, double value, Noise noise, std::uint64_t seed) {
    ForcesMeasured m = measured;
    std::mt19937_64 rng(seed);
    const auto e = make_noise(noise, m, rng);
    for (size_t i = 0; i < m.data.rows.size(); ++i) {
      auto& row = m.data.rows[i];
      const int k = row.group == "cycle 1" ? 0 : 1;
      row.value = sim->run(truth, value, k)->share(row.x) * m.total_N[i] + e[i];
    }
    return m;
  }
  // RMS of (simulated axial contact force - applied total) over the rows, no effect [N]
  double contact_force_gap_rms() {
    double sum = 0.0;
    for (size_t i = 0; i < measured.data.rows.size(); ++i) {
      const auto& row = measured.data.rows[i];
      const auto t = sim->run(Effect::none, 0.0, row.group == "cycle 1" ? 0 : 1);
      const double gap = t->at(true, row.x) + t->at(false, row.x) - measured.total_N[i];
      sum += gap * gap;
    }
    return std::sqrt(sum / static_cast<double>(measured.data.rows.size()));
  }
};

}  // namespace

TEST_CASE("forces diagnosis: hidden load-line shifts and stance VV moments are named, none is "
          "never named") {
  Fixture f;
  REQUIRE(f.measured.two_cycles);
  REQUIRE(f.measured.cycles.size() == 2);
  MESSAGE("simulated axial contact force against the applied total: RMS gap "
          << f.contact_force_gap_rms() << " N (not in the synthetic medial force)");
  DiagnosisOptions options;
  options.bootstrap = 50;
  struct Trial {
    Effect truth;
    double value;  // [mm]
    Noise noise;
  };
  // magnitudes a rig-to-patient comparison shows (the JW load line sits about 8 mm from the
  // rig's); both signs; every noise model for every truth (the load-line detection limit the
  // diagnosis reports for a clean record is about 1.5-1.8 mm, forces_correlated_test)
  const std::vector<Trial> trials = {
      {Effect::none, 0.0, Noise::white},         {Effect::none, 0.0, Noise::drift},
      {Effect::none, 0.0, Noise::proportional},  {Effect::load_line, 6.0, Noise::white},
      {Effect::load_line, -6.0, Noise::drift},   {Effect::load_line, 7.0, Noise::proportional},
      {Effect::vv_moment, 8.0, Noise::white},    {Effect::vv_moment, -6.0, Noise::drift},
      {Effect::vv_moment, 5.0, Noise::proportional}};
  int named = 0, false_positives = 0, effects = 0;
  std::uint64_t seed = 11;
  for (const Trial& t : trials) {
    const ForcesMeasured m = f.synthetic(t.truth, t.value, t.noise, seed++);
    const DiagnosisCase c = make_forces_case(m, f.sim);
    const ForcesDiagnosisReport rep = diagnose_forces(c, *f.sim, m.total_N, options);
    const ModelFit& e = rep.result.extended();
    INFO("truth " << effect_name(t.truth) << " " << t.value << ", noise " << std::string(noise_name(t.noise))
                  << ": named " << effect_name(e.effect) << ", gain " << rep.result.gain
                  << ", gain vs trivial " << rep.result.gain_vs_trivial);
    MESSAGE("truth " << effect_name(t.truth) << " " << t.value << " mm, noise "
                     << std::string(noise_name(t.noise)) << ": named " << effect_name(e.effect)
                     << (e.params.size() ? " " + std::to_string(e.params[0]) : std::string())
                     << ", gain " << rep.result.gain << ", gain vs trivial "
                     << rep.result.gain_vs_trivial << ", held-out RMSE none "
                     << rep.result.baseline.heldout_rmse << " N, named " << e.heldout_rmse
                     << " N");
    CHECK(e.effect == t.truth);
    if (t.truth == Effect::none) {
      false_positives += e.effect != Effect::none;
      continue;
    }
    ++effects;
    named += e.effect == t.truth;
    if (e.effect == t.truth) {
      // the fitted parameter recovers the hidden one, and its interval covers it
      CHECK(e.params[0] == doctest::Approx(t.value).epsilon(0.15));
      CHECK(e.ci_low[0] <= t.value + 0.5);
      CHECK(e.ci_high[0] >= t.value - 0.5);
      // the held-out gain against none: the instrument's offset and drift are refitted on the
      // held-out cycle, its gain and crosstalk are not carried over (at their prior mean 0,
      // forces_case.h), so none cannot follow a load-line shift there by borrowing a
      // calibration correction from the training cycle: gains 0.59-0.76 measured (with the
      // calibration carried they were 0.12 for the 6 and 7 mm shifts, the none model absorbing
      // the shift as a gain error). Larger shifts are no remedy: from about 8 mm the lateral
      // condyle lifts off at toe-off on this rig (8 mm fitted as 6.4, 8.5 mm named none)
      CHECK(rep.result.gain > 0.3);
      CHECK(rep.result.gain_vs_trivial > 0.0);
    }
  }
  MESSAGE("named " << named << " of " << effects << " hidden effects, " << false_positives
                   << " false positives in 3 clean sets");
  CHECK(named == effects);
  CHECK(false_positives == 0);
}

TEST_CASE("kneesim diagnose forces writes the diagnosis end to end") {
  test::TempDir tmp;
  tmp.write("synthetic.csv", loads_table());
  const fs::path config = tmp.write("synthetic.toml", kConfig);
  const fs::path out = tmp.path / "diag";
  const test::Result r = test::run_kneesim(
      {"diagnose", "forces", "--config", config.string(), "--out", out.string(), "--bootstrap",
       "20"},
      tmp.path);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  for (const char* f : {"diagnosis.json", "diagnosis.md", "diagnosis.png", "residuals.csv"}) {
    CHECK_MESSAGE(fs::exists(out / f), "missing " << f);
  }
  const auto j = nlohmann::json::parse(test::slurp(out / "diagnosis.json"));
  for (const char* k : {"baseline", "effect", "extended", "gain", "candidates", "gain_vs_trivial"}) {
    CHECK_MESSAGE(j.contains(k), "diagnosis.json lacks " << k);
  }
  for (const char* k : {"model", "params", "params_ci95", "rmse", "heldout_rmse"}) {
    CHECK_MESSAGE(j["extended"].contains(k), "extended lacks " << k);
  }
  // the named effect (here the noise-free 0.6 share against the rig's 0.61) is a candidate
  const std::string effect = j["effect"];
  CHECK((effect == "none" || effect == "load_line" || effect == "vv_moment" ||
         effect == "vv_alignment"));
  // the error model and the detection limits are reported
  REQUIRE(j.contains("error_model"));
  CHECK(j["error_model"]["name"] == "instrument");
  CHECK(j["error_model"]["correlation"] == "ornstein_uhlenbeck");
  // offset, drift, gain difference, the two crosstalk directions
  CHECK(j["error_model"]["nuisance"].size() == 5);
  REQUIRE(j.contains("detection"));
  CHECK(j["detection"]["limits"].size() == 6);
  CHECK(j["candidates"][0].contains("nuisance"));
  const std::string md = test::slurp(out / "diagnosis.md");
  CHECK(md.find("## Error model") != std::string::npos);
  CHECK(md.find("## Detection limits") != std::string::npos);
  CHECK(md.find("never named as causes") != std::string::npos);
  if (effect == "none") CHECK(md.find("no effect larger than the limits below") != std::string::npos);
}

TEST_CASE("kneesim diagnose forces refuses an unknown noise model or noise key") {
  test::TempDir tmp;
  tmp.write("synthetic.csv", loads_table());
  const fs::path config = tmp.write("synthetic.toml", kConfig);
  const test::Result model = test::run_kneesim(
      {"diagnose", "forces", "--config", config.string(), "--out", (tmp.path / "a").string(),
       "--noise-model", "pink"},
      tmp.path);
  CHECK(model.exit_code == 2);
  CHECK(model.err.find("--noise-model 'pink' does not exist; allowed: white, correlated, "
                       "instrument.") != std::string::npos);
  const test::Result key = test::run_kneesim(
      {"diagnose", "forces", "--config", config.string(), "--out", (tmp.path / "b").string(),
       "--noise-param", "crosstalk_sd=0.01"},
      tmp.path);
  CHECK(key.exit_code == 2);
  CHECK(key.err.find("--noise-param 'crosstalk_sd' is not a key of the forces error model; "
                     "allowed: ou, specimen_offset, gain_crosstalk_sd") != std::string::npos);
  const test::Result value = test::run_kneesim(
      {"diagnose", "forces", "--config", config.string(), "--out", (tmp.path / "c").string(),
       "--noise-param", "gain_crosstalk_sd=x"},
      tmp.path);
  CHECK(value.exit_code == 2);
  CHECK(value.err.find("--noise-param 'gain_crosstalk_sd=x' is not key=value with a number") !=
        std::string::npos);
}

TEST_CASE("kneesim diagnose forces refuses data without the medial channel") {
  test::TempDir tmp;
  tmp.write("synthetic.csv", loads_table());
  std::string cfg = kConfig;
  cfg.replace(cfg.find("compare = "), std::string("compare = [\"medial_force_N = medial_N\"]").size(),
              "compare = []");
  const fs::path config = tmp.write("nomedial.toml", cfg);
  const test::Result r = test::run_kneesim(
      {"diagnose", "forces", "--config", config.string(), "--out", (tmp.path / "d").string()},
      tmp.path);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("medial_force_N") != std::string::npos);
  CHECK(r.err.find("nomedial.toml") != std::string::npos);
}
