// Reference: the determinism rule of design.md: the same inputs give bit-identical results for
// any thread count (row-wise FFT passes, fixed-order sums).
#include <doctest/doctest.h>
#include <omp.h>

#include "wear/particles/contact.h"
#include "wear/particles/stress.h"
#include "wear/particles/surface.h"

using namespace kneesim::particles;

TEST_CASE("contact pressure and von Mises field are bit-identical for 1 and 2 threads") {
  Grid g{64, 64, 102e-9, 102e-9, true};
  const std::vector<double> rough = make_rough_surface(g, SurfaceSpec{300e-9, -0.5, 4.0, 1e-6, 5}, "t");
  std::vector<double> h(g.size());
  for (int i = 0; i < g.nx; ++i)
    for (int j = 0; j < g.ny; ++j) h[i * g.ny + j] = g.x(i) * g.x(i) / 4e-3 - rough[i * g.ny + j];
  const ElasticBody steel{210e9, 0.3};
  ContactOptions opt;
  opt.load = 0.02;
  opt.hardness = 1.8e9;
  opt.max_iterations = 200;
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    DeflectionOperator op(g, steel, steel);
    ContactResult r = solve_contact(op, h, opt);
    SubsurfaceStress st(g, 0.3);
    st.set_traction(r.pressure, 0.16);
    std::vector<double> vm = calc_von_mises_field(st, 4, 95e-9);
    r.pressure.insert(r.pressure.end(), vm.begin(), vm.end());
    return r.pressure;
  };
  const int saved = omp_get_max_threads();
  const std::vector<double> a = run(1), b = run(2);
  omp_set_num_threads(saved);
  CHECK(a == b);
}
