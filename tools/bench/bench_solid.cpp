// bench_solid: hex8 element updates per second (engine/solid) on 1 and 2 threads, on an idle
// machine and with one core kept busy by a spinning child process the bench starts itself
// (issue 30's acceptance figures; not part of ctest).
//
// A UHMWPE block of nx x ny x nz elements, its base fixed and its top loaded, stepped at 0.7
// of the stable step (elastic, or J2 with --plastic). An "update" is one element of a whole
// step_solid (element kernel with the fused force gather, node update), so the rate is the
// solid's throughput, not the kernel's alone. The thread counts run alternately (1, 2, 1, 2,
// ...) and each figure is the median over the repeats, so a drift of the machine's speed
// hits both alike. Two figures per run: updates per wall-clock second (what a run sees) and
// per CPU second of the process (CLOCK_PROCESS_CPUTIME_ID).
//
// With --busy, a child process spins on one core during the measurement (a second program on
// the machine, as on a shared workstation or beside another MPI rank): the figure asked is
// 2 threads >= 0.9 x 1 thread there. The team's policy counts (engine/work_team.h: loops run
// solo, stalls, tasks the caller took over) are printed for the 2-thread runs.
//
//   bench_solid [nx ny nz] [steps] [repeats]         (default 40 20 12 = 9600 elements, 300, 5)
//   bench_solid [--mesh nx ny nz] [--steps N] [--repeats R] [--plastic] [--busy] [--idle-and-busy]
//               [--isa baseline|avx2|avx512] [--fixed-team] [--threads A,B]
//
// --idle-and-busy measures both conditions one after the other and prints the acceptance table.
// --fixed-team switches the team's never-slower policy off (the team runs every loop).
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "busy_core.h"
#include "engine/solid/solid_build.h"
#include "engine/solid/solid_step.h"
#include "models/hex_mesh.h"

using namespace kneesim;
namespace sol = kneesim::engine::solid;

namespace {

std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c, d;
  f >> a >> b >> c >> d;
  return a + " " + b + " " + c + " (running " + d + ")";
}

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Options {
  int nx = 40, ny = 20, nz = 12, steps = 300, repeats = 5;
  bool plastic = false, fixed_team = false;
  int busy = 0;  // 0 idle, 1 busy, 2 both
  std::vector<int> threads = {1, 2};
  sol::Hex8Isa isa = sol::hex8_batch_best_isa();
};

[[noreturn]] void usage(const char* why) {
  std::fprintf(stderr,
               "bench_solid: %s\nusage: bench_solid [nx ny nz] [steps] [repeats] | [--mesh nx ny "
               "nz] [--steps N] [--repeats R] [--plastic] [--busy] [--idle-and-busy] [--isa "
               "baseline|avx2|avx512] [--fixed-team] [--threads A,B]\n",
               why);
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  if (argc > 1 && argv[1][0] != '-') {  // the positional form
    if (argc > 3) {
      o.nx = std::atoi(argv[1]);
      o.ny = std::atoi(argv[2]);
      o.nz = std::atoi(argv[3]);
    }
    if (argc > 4) o.steps = std::atoi(argv[4]);
    if (argc > 5) o.repeats = std::atoi(argv[5]);
  } else {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      const auto next = [&]() -> const char* {
        if (i + 1 >= argc) usage(("missing value after " + a).c_str());
        return argv[++i];
      };
      if (a == "--mesh") {
        o.nx = std::atoi(next());
        o.ny = std::atoi(next());
        o.nz = std::atoi(next());
      } else if (a == "--steps") {
        o.steps = std::atoi(next());
      } else if (a == "--repeats") {
        o.repeats = std::atoi(next());
      } else if (a == "--plastic") {
        o.plastic = true;
      } else if (a == "--busy") {
        o.busy = 1;
      } else if (a == "--idle-and-busy") {
        o.busy = 2;
      } else if (a == "--fixed-team") {
        o.fixed_team = true;
      } else if (a == "--isa") {
        const std::string v = next();
        if (v == "baseline") o.isa = sol::Hex8Isa::kBaseline;
        else if (v == "avx2") o.isa = sol::Hex8Isa::kAvx2;
        else if (v == "avx512") o.isa = sol::Hex8Isa::kAvx512;
        else usage(("--isa " + v + " is not one of baseline, avx2, avx512").c_str());
        if (!sol::hex8_batch_supports(o.isa)) usage(("this CPU has no " + v).c_str());
      } else if (a == "--threads") {
        o.threads.clear();
        for (std::string s = next(); !s.empty();) {
          const size_t c = s.find(',');
          o.threads.push_back(std::atoi(s.substr(0, c).c_str()));
          s = c == std::string::npos ? "" : s.substr(c + 1);
        }
      } else {
        usage(("unknown option " + a).c_str());
      }
    }
  }
  if (o.nx < 1 || o.ny < 1 || o.nz < 1 || o.steps < 1 || o.repeats < 1 || o.threads.empty())
    usage("nx ny nz steps repeats must be >= 1");
  for (int t : o.threads)
    if (t < 1 || t > 64) usage("thread counts must be 1..64");
  return o;
}

struct Result {
  double wall_rate = 0, cpu_rate = 0;  // M updates per wall / CPU second, medians
  double wall_min = 0, wall_max = 0;   // M updates per wall second
  engine::WorkTeamStats stats;
};

struct Bench {
  const Options& o;
  models::HexMesh mesh;
  sol::SolidMaterial mat;
  std::vector<uint8_t> fix;
  Eigen::Vector3d size{0.04, 0.02, 0.012};

  explicit Bench(const Options& options) : o(options) {
    mesh = models::make_box_hex_mesh(o.nx, o.ny, o.nz, size);
    mat.youngs_modulus = 685e6;
    mat.poisson = 0.47;
    mat.density = 935.0;
    if (o.plastic) {
      mat.kind = sol::SolidMaterialKind::kJ2Plastic;
      mat.yield_stress = 17e6;
      mat.hardening_modulus = 50e6;
      mat.yield_cap = 33e6;
    }
    fix.assign(mesh.nodes.size(), 0);
    for (size_t n = 0; n < mesh.nodes.size(); ++n)
      if (mesh.nodes[n].z() == 0.0) fix[n] = sol::kFixAll;
  }

  // one timed run of `threads`: wall and CPU seconds
  std::pair<double, double> run(const sol::SolidModel& model, engine::WorkTeamStats& stats) const {
    sol::SolidState state = sol::make_solid_state(model);
    sol::SolidData data = sol::make_solid_data(model);
    if (engine::WorkTeam* team = data.team.get()) team->set_adaptive(!o.fixed_team);
    // the top pressed hard enough that a J2 block yields under it (50 MPa on the top face)
    const double load = o.plastic ? -50e6 * size.x() * size.y() / ((o.nx + 1) * (o.ny + 1)) : -1.0;
    for (size_t n = 0; n < mesh.nodes.size(); ++n)
      if (mesh.nodes[n].z() == size.z()) data.external_force[n] = Eigen::Vector3d(0.1 * -load, 0, load);
    const double c0 = process_cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    for (int s = 0; s < o.steps; ++s) {
      if (sol::step_solid(model, state, data, 0.7 * model.dt_critical) != sol::SolidStatus::kOk) {
        std::fprintf(stderr, "bench_solid: step %d failed (inverted element)\n", s);
        std::exit(1);
      }
    }
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = process_cpu_seconds() - c0;
    if (const engine::WorkTeam* team = data.team.get()) {
      const engine::WorkTeamStats& s = team->stats();
      stats.loops += s.loops;
      stats.solo_loops += s.solo_loops;
      stats.stalls += s.stalls;
      stats.stolen_tasks += s.stolen_tasks;
      stats.unhelped_loops += s.unhelped_loops;
      stats.solo_switches += s.solo_switches;
    }
    return {wall, cpu};
  }

  std::vector<Result> measure() const {
    std::vector<sol::SolidModel> models;
    for (int t : o.threads) {
      sol::SolidOptions options;
      options.threads = t;
      models.push_back(sol::make_solid_model(mesh.nodes, mesh.elements, mat, options, fix));
    }
    const double updates = static_cast<double>(models[0].num_elements()) * o.steps;
    std::vector<std::vector<double>> wall(o.threads.size()), cpu(o.threads.size());
    std::vector<Result> out(o.threads.size());
    for (int r = 0; r < o.repeats; ++r) {
      for (size_t k = 0; k < o.threads.size(); ++k) {
        const auto [w, c] = run(models[k], out[k].stats);
        wall[k].push_back(updates / w / 1e6);
        cpu[k].push_back(updates / c / 1e6);
      }
    }
    for (size_t k = 0; k < o.threads.size(); ++k) {
      out[k].wall_rate = median(wall[k]);
      out[k].cpu_rate = median(cpu[k]);
      out[k].wall_min = *std::min_element(wall[k].begin(), wall[k].end());
      out[k].wall_max = *std::max_element(wall[k].begin(), wall[k].end());
    }
    return out;
  }
};

std::vector<Result> measure_condition(const Bench& bench, const Options& o, bool busy) {
  pid_t spinner = busy ? bench::start_busy_core("bench_solid") : 0;
  std::printf("\n%s: load average before %s\n", busy ? "one core busy (spinning child)" : "idle",
              load_average().c_str());
  const std::vector<Result> r = bench.measure();
  std::printf("| threads | M updates / wall s, median (min-max) | M updates / CPU s | team loops "
              "solo / all | stalls | tasks taken over | loops the helpers did not help | solo switches |\n|---|---|---|---|---|---|---|---|\n");
  for (size_t k = 0; k < o.threads.size(); ++k) {
    std::printf("| %d | %.2f (%.2f-%.2f) | %.2f | %ld / %ld | %ld | %ld | %ld | %ld |\n",
                o.threads[k], r[k].wall_rate, r[k].wall_min, r[k].wall_max, r[k].cpu_rate,
                r[k].stats.solo_loops, r[k].stats.loops, r[k].stats.stalls,
                r[k].stats.stolen_tasks, r[k].stats.unhelped_loops, r[k].stats.solo_switches);
  }
  std::printf("load average after %s\n", load_average().c_str());
  if (busy) bench::stop_busy_core(spinner);
  std::fflush(stdout);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  sol::set_hex8_batch_isa(o.isa);
  const Bench bench(o);
  const char* wait = std::getenv("OMP_WAIT_POLICY");
  std::printf("bench_solid: %d elements (%s), %zu nodes, %d steps per run, median of %d "
              "alternating runs; kernel %s; %ld CPUs online; OMP_WAIT_POLICY=%s (not used by the "
              "solid)\n",
              o.nx * o.ny * o.nz, o.plastic ? "J2 UHMWPE, top at 50 MPa" : "elastic UHMWPE",
              bench.mesh.nodes.size(), o.steps, o.repeats, sol::to_string(o.isa),
              sysconf(_SC_NPROCESSORS_ONLN), wait ? wait : "(unset)");
  std::vector<Result> idle, busy;
  if (o.busy != 1) idle = measure_condition(bench, o, false);
  if (o.busy != 0) busy = measure_condition(bench, o, true);
  // the acceptance lines of issue 30 when 1 and 2 threads were measured
  const auto at = [&](int t) -> int {
    for (size_t k = 0; k < o.threads.size(); ++k)
      if (o.threads[k] == t) return static_cast<int>(k);
    return -1;
  };
  const int k1 = at(1), k2 = at(2);
  if (k1 < 0 || k2 < 0) return 0;
  std::printf("\n| acceptance (issue 30) | measured | asked |\n|---|---|---|\n");
  if (!idle.empty()) {
    std::printf("| 2 threads, M updates/s (idle machine) | %.2f | >= 50 |\n", idle[k2].wall_rate);
    std::printf("| 2 threads / 1 thread (idle machine) | %.2f | >= 1.8 |\n",
                idle[k2].wall_rate / idle[k1].wall_rate);
  }
  if (!busy.empty()) {
    std::printf("| 2 threads / 1 thread, one core busy | %.2f | >= 0.9 |\n",
                busy[k2].wall_rate / busy[k1].wall_rate);
  }
  std::printf("(the idle figures count only when the load average before them was near 0)\n");
  return 0;
}
