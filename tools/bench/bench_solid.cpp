// bench_solid: elastic hex8 element updates per second (engine/solid) on 1 and 2 threads.
// A UHMWPE block of nx x ny x nz elements, its base fixed and its top loaded, stepped at 0.7
// of the stable step; each configuration runs `repeats` times and the median is reported,
// with the thread ratio measured in the same run. An "update" is one element of a whole
// step_solid (element kernel, gather to the nodes, node update), so the rate is the solid's
// throughput, not the kernel's alone.
//
// Two figures per thread count: updates per wall-clock second (what a run sees; on a loaded
// machine it measures the share of the cores the process got) and updates per CPU second of
// the process (CLOCK_PROCESS_CPUTIME_ID: nearly load-independent with OMP_WAIT_POLICY=passive,
// where a waiting thread sleeps instead of spinning on the CPU clock). The load average is
// printed before and after; run with OMP_WAIT_POLICY=passive on a shared machine.
//
//   bench_solid [nx ny nz] [steps] [repeats]     (default 40 20 12 = 9600 elements, 300, 5)
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "engine/solid/solid_build.h"
#include "engine/solid/solid_step.h"
#include "models/hex_mesh.h"

using namespace kneesim;

namespace {

std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  f >> a >> b >> c;
  return a + " " + b + " " + c;
}

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int nx = argc > 3 ? std::atoi(argv[1]) : 40, ny = argc > 3 ? std::atoi(argv[2]) : 20,
            nz = argc > 3 ? std::atoi(argv[3]) : 12;
  const int steps = argc > 4 ? std::atoi(argv[4]) : 300;
  const int repeats = argc > 5 ? std::atoi(argv[5]) : 5;
  if (nx < 1 || ny < 1 || nz < 1 || steps < 1 || repeats < 1) {
    std::fprintf(stderr, "bench_solid: nx ny nz steps repeats must be >= 1\n");
    return 2;
  }
  const Eigen::Vector3d size(0.04, 0.02, 0.012);
  const models::HexMesh mesh = models::make_box_hex_mesh(nx, ny, nz, size);
  engine::solid::SolidMaterial mat;
  mat.youngs_modulus = 685e6;
  mat.poisson = 0.47;
  mat.density = 935.0;
  std::vector<uint8_t> fix(mesh.nodes.size(), 0);
  for (size_t n = 0; n < mesh.nodes.size(); ++n)
    if (mesh.nodes[n].z() == 0.0) fix[n] = engine::solid::kFixAll;
  const char* wait = std::getenv("OMP_WAIT_POLICY");
  std::printf("bench_solid: %d elements, %zu nodes, %d steps, median of %d; kernel %s; "
              "OMP_WAIT_POLICY=%s; load average %s\n",
              nx * ny * nz, mesh.nodes.size(), steps, repeats,
              engine::solid::hex8_batch_has_avx2() ? "AVX2" : "baseline x86-64",
              wait ? wait : "(unset)", load_average().c_str());
  double rate[3] = {0, 0, 0};
  for (int threads : {1, 2}) {
    engine::solid::SolidOptions options;
    options.threads = threads;
    const engine::solid::SolidModel model =
        engine::solid::make_solid_model(mesh.nodes, mesh.elements, mat, options, fix);
    std::vector<double> wall, cpu;
    for (int r = 0; r < repeats; ++r) {
      engine::solid::SolidState state = engine::solid::make_solid_state(model);
      engine::solid::SolidData data = engine::solid::make_solid_data(model);
      for (size_t n = 0; n < mesh.nodes.size(); ++n)
        if (mesh.nodes[n].z() == size.z()) data.external_force[n] = Eigen::Vector3d(0.1, 0, -1.0);
      const double c0 = process_cpu_seconds();
      const auto t0 = std::chrono::steady_clock::now();
      for (int s = 0; s < steps; ++s) {
        if (engine::solid::step_solid(model, state, data, 0.7 * model.dt_critical) !=
            engine::solid::SolidStatus::kOk) {
          std::fprintf(stderr, "bench_solid: step %d failed\n", s);
          return 1;
        }
      }
      wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      cpu.push_back(process_cpu_seconds() - c0);
    }
    const double updates = static_cast<double>(model.num_elements()) * steps;
    const double w = median(wall), c = median(cpu);
    rate[threads] = updates / w;
    std::printf("threads %d: wall median %.4f s (min %.4f, max %.4f), %.2f M element-updates/s; "
                "CPU median %.4f s, %.2f M element-updates per CPU second\n",
                threads, w, *std::min_element(wall.begin(), wall.end()),
                *std::max_element(wall.begin(), wall.end()), rate[threads] / 1e6, c,
                updates / c / 1e6);
  }
  std::printf("2-thread / 1-thread rate (wall): %.2f; load average after %s\n", rate[2] / rate[1],
              load_average().c_str());
  return 0;
}
