// Benchmark of the particle BEM (issue 5 targets on this machine, Release):
//   a 256 x 256 rough contact solve <= 0.5 s, the 256 x 256 x 64 von Mises field <= 2 s;
// medians of repeated runs, plus the one-off operator set-up, and a grid convergence study
// 80^2 .. 320^2 over the same physical window (each grid generates the same physical surfaces),
// first contact and the full wear loop.
// Usage: bench_particles [repeats=5] [--no-convergence] [--lambda-s-nm L]
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <functional>
#include <memory>
#include <vector>

#include "wear/particles/contact.h"
#include "wear/particles/detachment.h"
#include "wear/particles/pairs.h"
#include "wear/particles/particle_model.h"
#include "wear/particles/stress.h"
#include "wear/particles/surface.h"

using namespace kneesim::particles;

namespace {

double cpu_now() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// wall seconds of f; also accumulates its process CPU seconds (all threads) into *cpu, which
// on a machine shared with other jobs is the better measure of the work done
double seconds_of(const std::function<void()>& f, double* cpu = nullptr) {
  const double c0 = cpu_now();
  const auto t0 = std::chrono::steady_clock::now();
  f();
  if (cpu != nullptr) *cpu = cpu_now() - c0;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 && argv[1][0] != '-' ? std::atoi(argv[1]) : 5;
  bool convergence = true;
  double lambda_s = -1.0;  // [m]; < 0: the preset's
  for (int a = 1; a < argc; ++a) {
    convergence = convergence && std::strcmp(argv[a], "--no-convergence") != 0;
    if (std::strcmp(argv[a], "--lambda-s-nm") == 0 && a + 1 < argc) lambda_s = 1e-9 * std::atof(argv[a + 1]);
  }
  std::printf("threads %d, FFT %s\n", omp_get_max_threads(), Fft2::backend());

  // the steel-steel case of the study on a 256 x 256 window (dx = 102 nm), 10 N
  ParticleModelConfig c = make_pair_config(PairName::kSteelSteel);
  if (lambda_s >= 0.0) c.harder.roughness.lambda_s = c.softer.roughness.lambda_s = lambda_s;
  const double window = 24.48e-6;
  const int n = 256;
  Grid g{n, n, window / n, window / n, true};
  c.grid = g;
  const std::vector<double> cyl = make_rough_surface(g, c.harder.roughness, "bench");
  const std::vector<double> disk = make_rough_surface(g, c.softer.roughness, "bench");
  std::vector<double> h(g.size());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      h[i * n + j] = g.x(i) * g.x(i) / (2 * c.cylinder_radius) - cyl[i * n + j] - disk[i * n + j];
  ContactOptions opt;
  opt.load = window_load(c);
  opt.hardness = c.softer.hardness;
  opt.tolerance = 1e-6;
  opt.max_iterations = 100;

  std::vector<double> t_setup, t_solve, t_field, c_solve, c_field;
  ContactResult cr;
  for (int r = 0; r < repeats; ++r) {
    std::unique_ptr<DeflectionOperator> op;
    double cpu = 0.0;
    t_setup.push_back(seconds_of([&] { op = std::make_unique<DeflectionOperator>(g, c.harder.elastic, c.softer.elastic); }));
    t_solve.push_back(seconds_of([&] { cr = solve_contact(*op, h, opt); }, &cpu));
    c_solve.push_back(cpu);
  }
  SubsurfaceStress st(g, c.softer.elastic.poisson_ratio);
  st.set_traction(cr.pressure, c.friction);
  std::vector<double> vm;
  for (int r = 0; r < repeats; ++r) {
    double cpu = 0.0;
    t_field.push_back(seconds_of([&] { vm = calc_von_mises_field(st, 64, 95e-9); }, &cpu));
    c_field.push_back(cpu);
  }
  std::printf("256x256 rough contact solve: median %.3f s wall, %.3f s CPU (CG iterations %d, "
              "converged %d, contact %.3f, capped %.3f)\n",
              median(t_solve), median(c_solve), cr.iterations, int(cr.converged), cr.contact_fraction, cr.capped_fraction);
  std::printf("256x256 deflection operator set-up (once per grid): median %.3f s\n", median(t_setup));
  std::printf("256x256x64 von Mises field: median %.3f s wall, %.3f s CPU (max %.0f MPa)\n",
              median(t_field), median(c_field),
              *std::max_element(vm.begin(), vm.end()) / 1e6);

  // smooth Hertz cylinder on the same grid (elastic; the CG without the cap)
  {
    std::vector<double> hs(g.size());
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) hs[i * n + j] = g.x(i) * g.x(i) / (2 * c.cylinder_radius);
    DeflectionOperator op(g, c.harder.elastic, c.softer.elastic);
    ContactOptions o2 = opt;
    o2.hardness = 0.0;
    o2.max_iterations = 2000;
    std::vector<double> ts;
    ContactResult r2;
    for (int r = 0; r < repeats; ++r) ts.push_back(seconds_of([&] { r2 = solve_contact(op, hs, o2); }));
    std::printf("256x256 smooth cylinder solve: median %.3f s (CG iterations %d)\n", median(ts), r2.iterations);
  }
  if (!convergence) return 0;

  // grid convergence: the same physical surfaces (same modes, same phases) on every grid over
  // the same window, the first contact
  std::printf("\ngrid convergence (steel-steel, 10 N, window %.2f um, lambda_s %.0f / %.0f nm, "
              "first contact, 16 levels refined x4)\n",
              window * 1e6, c.harder.roughness.lambda_s * 1e9, c.softer.roughness.lambda_s * 1e9);
  std::printf("   n   dx_nm  contact  capped  maxvM_MPa  particles  R_nm  L_nm  W_nm  T_nm  solve_s  field_s\n");
  for (int m : {80, 120, 160, 240, 320}) {
    Grid gm{m, m, window / m, window / m, true};
    const std::vector<double> cm = make_rough_surface(gm, c.harder.roughness, "bench");
    const std::vector<double> dm = make_rough_surface(gm, c.softer.roughness, "bench");
    std::vector<double> hm(gm.size());
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j)
        hm[i * m + j] = gm.x(i) * gm.x(i) / (2 * c.cylinder_radius) - cm[i * m + j] - dm[i * m + j];
    DeflectionOperator op(gm, c.harder.elastic, c.softer.elastic);
    ContactResult rm;
    const double ts = seconds_of([&] { rm = solve_contact(op, hm, opt); });
    SubsurfaceStress sm(gm, 0.3);
    sm.set_traction(rm.pressure, c.friction);
    // the criterion on the standard vertical grid (16 levels of 95 nm refined x4), and with
    // the levels halved (32 of 47.5 nm) to check the vertical refinement
    for (int half = 0; half <= (m == 240 ? 1 : 0); ++half) {
      const int nz = half ? 32 : 16;
      const double dz = half ? 47.5e-9 : 95e-9;
      std::vector<double> vmm;
      const double tf = seconds_of([&] { vmm = calc_von_mises_field(sm, nz, dz); });
      const Detachment d = find_particles(refine_levels(vmm, gm.size(), nz, 4), gm, (nz - 1) * 4,
                                          dz / 4, c.softer.yield_stress);
      std::vector<ParticleRecord> recs;
      for (const Particle& p : d.particles) recs.push_back({1, p});
      const SizeStats s = calc_size_stats(recs, 1);
      std::printf("%4d%s  %6.1f  %7.4f  %6.4f  %9.0f  %9ld  %4.0f  %4.0f  %4.0f  %4.0f  %7.3f  %7.3f\n", m,
                  half ? "h" : " ", gm.dx * 1e9, rm.contact_fraction, rm.capped_fraction,
                  *std::max_element(vmm.begin(), vmm.end()) / 1e6, s.particles, s.eq_radius * 1e9,
                  s.length * 1e9, s.width * 1e9, s.thickness * 1e9, ts, tf);
    }
  }

  // the wear loop on the same grids: preset surfaces and run settings, the window and the
  // sliding step per iteration (30 cells of 102 nm = 3.06 um) held fixed in physical units
  std::printf("\nwear-loop grid convergence (steel-steel, 10 N, default loop, window %.2f um)\n", window * 1e6);
  std::printf("   n   dx_nm  iterations  particles  R_nm  L_nm  W_nm  T_nm  seconds\n");
  for (int m : {80, 120, 160, 240, 320}) {
    ParticleModelConfig cw = make_pair_config(PairName::kSteelSteel);
    if (lambda_s >= 0.0) cw.harder.roughness.lambda_s = cw.softer.roughness.lambda_s = lambda_s;
    cw.grid = Grid{m, m, window / m, window / m, true};
    cw.slide_cells = static_cast<int>(std::lround(30 * 102e-9 / cw.grid.dx));
    const ParticleModelResult r = run_particle_model(cw, "bench");
    std::printf("%4d  %6.1f  %10zu  %9ld  %4.0f  %4.0f  %4.0f  %4.0f  %7.1f\n", m, cw.grid.dx * 1e9,
                r.iterations.size(), r.steady.particles, r.steady.eq_radius * 1e9,
                r.steady.length * 1e9, r.steady.width * 1e9, r.steady.thickness * 1e9, r.seconds);
  }
  return 0;
}
