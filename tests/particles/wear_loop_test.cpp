// The particle wear loop's run length (wear/particles/particle_model.h). References: the pass
// arithmetic (a pass = ceil(track rows / slide_cells) iterations); and an exact invariant: when
// nothing detaches, the track never changes, so with a slide that divides the track every
// later pass would repeat the first one and the loop stops after one pass.
#include <doctest/doctest.h>

#include "wear/particles/particle_model.h"

using namespace kneesim::particles;

TEST_CASE("run lengths: automatic limits are whole passes of the track; explicit ones are kept") {
  ParticleModelConfig c = make_pair_config(PairName::kSteelSteel);
  c.grid.nx = 240;
  c.track_factor = 2;
  c.slide_cells = 30;
  RunLengths r = resolve_run_lengths(c);
  CHECK(r.pass == 16);  // 480 track rows / 30
  CHECK(r.block == 16);
  CHECK(r.min_iterations == 48);
  CHECK(r.max_iterations == 192);
  c.slide_cells = 50;  // 480 / 50 = 9.6: a partial last step still belongs to the pass
  CHECK(resolve_run_lengths(c).pass == 10);
  c.block = 4;
  c.min_iterations = 30;
  c.max_iterations = 20;  // min is clamped to max
  r = resolve_run_lengths(c);
  CHECK(r.block == 4);
  CHECK(r.max_iterations == 20);
  CHECK(r.min_iterations == 20);
}

TEST_CASE("wear loop: no yielded region reaches the surface -> one pass, steady, no particles") {
  ParticleModelConfig c = make_pair_config(PairName::kSteelSteel);
  c.grid = Grid{64, 64, 102e-9, 102e-9, true};
  c.nz = 16;
  c.slide_cells = 16;                // track 128 rows: a pass of 8 iterations
  c.load = 0.05;
  c.softer.yield_stress = 1e12;      // nothing can yield
  const ParticleModelResult r = run_particle_model(c, "test");
  CHECK(r.particles.empty());
  CHECK(r.steady_state);
  CHECK(r.iterations.size() == static_cast<size_t>(resolve_run_lengths(c).pass));
  CHECK(resolve_run_lengths(c).pass == 8);
}
