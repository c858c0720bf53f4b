// The diagnosis framework on the block-on-ring case: output keys, bootstrap determinism,
// input validation (one sentence naming file, row and column), the split rule; the time of a
// diagnosis is reported.
#include <doctest/doctest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "analysis/diagnosis/bor_case.h"
#include "analysis/diagnosis/diagnose.h"
#include "analysis/diagnosis/report.h"
#include "engine/errors.h"
#include "tests/diagnosis/hidden_effect.h"

using namespace kneesim;
using namespace kneesim::diagnosis;

namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "kneesim_test_diagnosis";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

std::string error_of(const std::string& csv_text) {
  const std::string path = write_temp("bad.csv", csv_text);
  try {
    make_bor_case(read_bor_measured(path), BorCaseOptions{});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* kGood =
    "load_N,cycles,volume_mm3\n"
    "225,50000,0.8\n225,100000,1.3\n225,150000,1.8\n225,200000,2.3\n"
    "130,50000,0.5\n130,100000,0.8\n130,150000,1.1\n130,200000,1.4\n";

}  // namespace

TEST_CASE("diagnosis.json carries exactly the keys of issue 4") {
  const auto s = test::make_synthetic_bor(Effect::running_in, 7);
  const auto c = make_bor_case(s.data, BorCaseOptions{});
  DiagnosisOptions opt;
  opt.bootstrap = 30;
  const auto r = diagnose(c, opt);
  const auto j = diagnosis_json(c, r);
  for (const char* key : {"baseline", "effect", "extended", "gain", "candidates"}) {
    CHECK(j.contains(key));
  }
  for (const char* key : {"model", "params", "rmse", "heldout_rmse"}) CHECK(j["baseline"].contains(key));
  for (const char* key : {"model", "params", "params_ci95", "rmse", "heldout_rmse"}) {
    CHECK(j["extended"].contains(key));
  }
  CHECK(j["effect"] == "running_in");
  CHECK(j["gain"].get<double>() ==
        doctest::Approx(1.0 - j["extended"]["heldout_rmse"].get<double>() /
                                  j["baseline"]["heldout_rmse"].get<double>()));
  CHECK(j["candidates"].size() == 5);  // none, running_in, incubation, pressure, creep
  for (const auto& cand : j["candidates"]) {
    for (const char* key : {"name", "params", "heldout_rmse", "aicc"}) CHECK(cand.contains(key));
  }
  // every fitted parameter has an interval that holds the estimate
  for (auto& [name, value] : j["extended"]["params"].items()) {
    const auto ci = j["extended"]["params_ci95"][name];
    CHECK(ci[0].get<double>() <= value.get<double>() * (1 + 1e-9));
    CHECK(ci[1].get<double>() >= value.get<double>() * (1 - 1e-9));
  }
  const std::string md = diagnosis_markdown(c, r);
  CHECK(md.find("Named cause: running_in") != std::string::npos);
  CHECK(residuals_csv(c, r).find("group,specimen,quantity,cycles,measured") == 0);
}

TEST_CASE("the bootstrap is deterministic for a seed and changes with it") {
  const auto s = test::make_synthetic_bor(Effect::pressure_dependent_wear, 11);
  const auto c = make_bor_case(s.data, BorCaseOptions{});
  DiagnosisOptions opt;
  opt.bootstrap = 40;
  opt.seed = 3;
  const auto a = diagnose(c, opt);
  const auto b = diagnose(c, opt);
  REQUIRE(a.extended().ci_low.size() == 2);
  CHECK(a.extended().ci_low == b.extended().ci_low);
  CHECK(a.extended().ci_high == b.extended().ci_high);
  opt.seed = 4;
  const auto d = diagnose(c, opt);
  CHECK(d.extended().ci_low != a.extended().ci_low);
}

TEST_CASE("the split rule follows the specimens") {
  const auto s = test::make_synthetic_bor(Effect::none, 1);
  const auto c = make_bor_case(s.data, BorCaseOptions{});
  CHECK(c.split_rule == "leave-one-specimen-out");
  CHECK(c.folds.size() == 12);  // 6 specimens x 2 loads
  const auto no_spec = make_bor_case(read_bor_measured(write_temp("good.csv", kGood)), {});
  CHECK(no_spec.split_rule == "leave-one-load-out");
  CHECK(no_spec.folds.size() == 2);
  CHECK(no_spec.candidates.size() == 3);  // no depth: creep is not a candidate
}

TEST_CASE("practitioner calibration recovers k_D from the steady-state slope") {
  // Hussin 2024: 0.5075 mm^3 per 50 000 cycles at 225 N gives k_D = 4.1e-10 mm^3/(N mm)
  const std::string csv =
      "load_N,cycles,volume_mm3\n225,50000,0.8380\n225,100000,1.3455\n225,150000,1.8530\n"
      "225,200000,2.3605\n130,50000,0.5332\n130,200000,1.41\n";
  const auto c = make_bor_case(read_bor_measured(write_temp("hussin.csv", csv)), {});
  const Eigen::VectorXd k = c.calibrate_baseline({0, 1, 2, 3, 4, 5});
  CHECK(k[0] == doctest::Approx(0.5075 / 5e4 / (225.0 * M_PI * 35.0)).epsilon(1e-9).scale(0));
  CHECK(k[0] == doctest::Approx(4.1e-10).epsilon(0.01).scale(0));
}

TEST_CASE("bad measured files give one sentence naming file, row and column") {
  CHECK(error_of("load_N,cycles\n225,1\n").find("no column 'volume_mm3'") != std::string::npos);
  const std::string nonnum = error_of("load_N,cycles,volume_mm3\n225,abc,1\n130,5,1\n");
  CHECK(nonnum.find("row 2, column cycles: 'abc' is not a number") != std::string::npos);
  const std::string neg = error_of("load_N,cycles,volume_mm3\n225,-5,1\n");
  CHECK(neg.find("row 2, column cycles: value -5 is outside") != std::string::npos);
  const std::string negv = error_of("load_N,cycles,volume_mm3\n225,5,1\n130,5,-0.1\n");
  CHECK(negv.find("row 3, column volume_mm3: value -0.1 is outside") != std::string::npos);
  const std::string single = error_of("load_N,cycles,volume_mm3\n225,5,1\n225,10,2\n");
  CHECK(single.find("column load_N") != std::string::npos);
  CHECK(single.find("two or more loads") != std::string::npos);
  const std::string fields = error_of("load_N,cycles,volume_mm3\n225,5\n");
  CHECK(fields.find("row 2 has 2 fields") != std::string::npos);
  for (const auto& e : {nonnum, neg, negv, single, fields}) {
    CHECK(e.find("bad.csv") != std::string::npos);
  }
  // volumes that fall with cycles at the calibration load (issue 15: a segfault in predict())
  const std::string falling = error_of(
      "load_N,cycles,volume_mm3\n225,50000,2\n225,100000,1.5\n225,150000,1\n225,200000,0.5\n"
      "130,50000,1\n130,100000,0.8\n130,150000,0.6\n130,200000,0.4\n");
  CHECK(falling.find("bad.csv: rows 2, 3, 4, 5, column volume_mm3 at the calibration load 225 N: "
                     "the volumes fall with cycles (slope -0.01 mm^3 per 1000 cycles); "
                     "cumulative wear volume must rise (slope > 0).") != std::string::npos);
  // fewer measurements than the parameters of a candidate
  const std::string few = write_temp(
      "few.csv", "load_N,cycles,volume_mm3\n225,50000,0.8\n225,100000,1.3\n130,50000,0.5\n"
                 "130,100000,0.8\n");
  const auto c = make_bor_case(read_bor_measured(few), {});
  try {
    diagnose(c, {});
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    const std::string msg = e.what();
    CHECK(msg.find("few.csv: rows 2-5, column volume_mm3") != std::string::npos);
    CHECK(msg.find("fewer than") != std::string::npos);
  }
}

TEST_CASE("a diagnosis of a few dozen measurements with 200 bootstrap resamples names creep") {
  // the time is reported, not asserted (a wall-clock limit makes a shared CI flaky)
  // 40 volume + 40 depth measurements (5 specimens x 2 loads x 4 cycle counts)
  const auto s = test::make_synthetic_bor(Effect::creep, 21);
  const auto t0 = std::chrono::steady_clock::now();
  const auto c = make_bor_case(s.data, BorCaseOptions{});
  const auto r = diagnose(c, DiagnosisOptions{});
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(r.effect() == Effect::creep);
  MESSAGE("BOR diagnosis of " << c.measured.rows.size() << " measurements, 200 bootstrap: "
                              << sec << " s");
}
