// The forces diagnosis' forward model is smooth in its parameters (default suite). Each 1 %
// sample of a forces simulation is the mean over its own 1 % of the cycle
// (analysis/diagnosis/forces_sim.h); sampled at an instant, the contact's fast oscillation on
// the faceted insert aliased into the medial force, which then jittered between close
// parameter values by about as much as the small identifiable part of a VV alignment's
// signal, and the diagnosis' interpolated grid and the detection replicates carried that
// jitter as if it were the effect.
//
// Reference (measured on the synthetic record of forces_synthetic.h, white_walk seed 1500):
// the second difference of the medial force over steps of 0.5 deg of femoral VV alignment about
// +-2 deg, RMS over the rows, was 12.9 and 13.8 N with samples at an instant and is 2.3 and
// 3.2 N with the mean (-tc="forces forward jitter" of test_diagnosis_forces_long prints both
// sizes and steps); the bound 6 N fails the instantaneous samples by a factor 2 and passes the
// mean by the same factor. The slope (about 19 N RMS per degree) is the signal it is compared
// with.
#include <doctest/doctest.h>

#include <cmath>

#include "tests/diagnosis_forces/forces_synthetic.h"

using namespace kneesim;
using namespace kneesim::diagnosis;
using namespace kneesim::test;

TEST_CASE("forces simulation: the medial force is smooth in the VV alignment (each sample the "
          "mean over its 1 % of the cycle)") {
  ForcesBench bench;
  const ForcesSet s0 = bench.make(Effect::none, 0.0, CellNoise::white_walk, 1500, 1.5);
  ForcesSimulator sim(bench.config(), s0.measured.cycles);
  sim.set_threads(2);
  const double root_n = std::sqrt(static_cast<double>(s0.measured.data.rows.size()));
  const double h = 0.5;
  for (double v0 : {-2.0, 2.0}) {
    const Eigen::VectorXd a = direct_medial(sim, s0.measured, Effect::vv_alignment, v0 - h);
    const Eigen::VectorXd b = direct_medial(sim, s0.measured, Effect::vv_alignment, v0);
    const Eigen::VectorXd c = direct_medial(sim, s0.measured, Effect::vv_alignment, v0 + h);
    const double second = (a - 2.0 * b + c).norm() / root_n;
    const double slope = (c - a).norm() / root_n / (2.0 * h);
    MESSAGE("alignment " << v0 << " deg: slope " << slope << " N/deg RMS, second difference over "
                         << h << " deg " << second << " N RMS");
    CHECK(second < 6.0);
    CHECK(slope > 10.0);  // the effect itself is there (about 19 N/deg)
  }
}
