// The forces diagnosis under instrument errors that are NOT its error model (issue 27), default
// suite: four-cell synthetic records (forces_synthetic.h) with a hidden effect whose
// identifiable signal is twice the record's noise RMS (the 1.2x tallies, with many seeds, are in
// forces_identification_long.cpp), and clean records. Required: the hidden effect named, clean
// records named none; on clean records the rig (driven by the filtered measured total, its
// share times the measured total) predicts the held-out cycle better than the trivial
// predictor (the issue measured 27.6 against 20.7 N and 54.9 against 17.0 N RMS, the rig
// losing, when the rig followed the raw noisy total); the detection limits are reported for
// every candidate and both signs, finite, and `none` reads "no effect larger than" them.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "tests/diagnosis_forces/forces_synthetic.h"

using namespace kneesim;
using namespace kneesim::diagnosis;
using namespace kneesim::test;

TEST_CASE("forces: hidden effects at twice the noise are named under cell noise of other "
          "families; clean records give none and the rig beats the trivial predictor") {
  ForcesBench bench;
  DiagnosisOptions opt;
  opt.bootstrap = 0;
  struct Trial {
    Effect truth;
    CellNoise noise;
    std::uint64_t seed;
  };
  const std::vector<Trial> trials = {
      {Effect::none, CellNoise::white_walk, 21},    {Effect::none, CellNoise::crosstalk, 22},
      {Effect::none, CellNoise::resonant, 23},      {Effect::load_line, CellNoise::crosstalk, 24},
      {Effect::vv_moment, CellNoise::pink, 25},     {Effect::vv_alignment, CellNoise::harmonic, 26}};
  for (const Trial& t : trials) {
    const ForcesSet s = bench.make_at_ratio(t.truth, 2.0, t.noise, t.seed);
    const ForcesDiagnosisReport rep = bench.diagnose(s, opt);
    const DiagnosisResult& r = rep.result;
    MESSAGE(effect_name(t.truth) << " (" << std::string(cell_noise_name(t.noise)) << ", seed " << t.seed
                                 << ", value " << s.value << ", noise " << s.noise_rms
                                 << " N, signal " << s.signal_rms << " N): named "
                                 << effect_name(r.effect()) << "; held-out RMSE rig "
                                 << r.baseline.heldout_rmse << " N, trivial "
                                 << r.trivial.heldout_rmse << " N, named "
                                 << r.extended().heldout_rmse << " N");
    CHECK(r.effect() == t.truth);
    if (t.truth == Effect::none) CHECK(r.baseline.heldout_rmse < r.trivial.heldout_rmse);
  }
}

TEST_CASE("forces: a clean record reports detection limits for every candidate and sign") {
  ForcesBench bench;
  DiagnosisOptions opt;
  opt.bootstrap = 0;
  opt.detection_replicates = 8;
  const ForcesSet s = bench.make_at_ratio(Effect::none, 1.2, CellNoise::white_walk, 31);
  const ForcesDiagnosisReport rep = bench.diagnose(s, opt);
  const DiagnosisResult& r = rep.result;
  REQUIRE(r.effect() == Effect::none);
  REQUIRE(r.detection.limits.size() == 6);  // three candidates, both signs
  for (const DetectionLimit& d : r.detection.limits) {
    MESSAGE(effect_name(d.effect) << " " << d.param << " " << (d.direction > 0 ? "+" : "-")
                                  << ": " << d.value << " (signal " << d.signal_rms << " N, "
                                  << d.ratio << " x noise " << r.detection.noise_rms << " N)");
    CHECK(d.direction * d.value > 0.0);
    CHECK(d.ratio > 0.1);
    CHECK(d.ratio < 5.0);
    // a VV alignment changes the medial share nearly uniformly over stance, which the cells'
    // gain and crosstalk terms also do: its limit may lie beyond the searched sizes (reported
    // as "not named up to"); the load line and the stance moment change the share's shape
    if (d.effect != Effect::vv_alignment) CHECK(d.reached);
    // the load-line limit against where the hidden-effect records start naming it: under this
    // family's noise (white_walk at 1.5 times its unit amplitude, 25-81 N RMS) fixed shifts of
    // 1, 1.5, 2 and 3 mm are named in 0, 2, 8 and 10 of 10 records (onset 2.0 mm;
    // docs/validation.md, forces hidden-effect tests); the limit must lie within a factor 1.5
    // of that onset
    if (d.effect == Effect::load_line) {
      CHECK(std::abs(d.value) > 2.0 / 1.5);
      CHECK(std::abs(d.value) < 2.0 * 1.5);
    }
  }
  // the fitted error model's noise against the record's: the same size (within a factor 2)
  CHECK(r.detection.noise_rms > 0.5 * s.noise_rms);
  CHECK(r.detection.noise_rms < 2.0 * s.noise_rms);
}
