// bench_solid: elastic hex8 element updates per second (engine/solid) on 1 and 2 threads.
// A UHMWPE block of nx x ny x nz elements, its base fixed and its top loaded, stepped at 0.7
// of the stable step; each configuration runs `repeats` times and the median is reported,
// with the thread ratio measured in the same run.
//
//   bench_solid [nx ny nz] [steps] [repeats]     (default 40 20 12 = 9600 elements, 300, 5)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "engine/solid/solid_build.h"
#include "engine/solid/solid_step.h"
#include "models/hex_mesh.h"

using namespace kneesim;

int main(int argc, char** argv) {
  const int nx = argc > 3 ? std::atoi(argv[1]) : 40, ny = argc > 3 ? std::atoi(argv[2]) : 20,
            nz = argc > 3 ? std::atoi(argv[3]) : 12;
  const int steps = argc > 4 ? std::atoi(argv[4]) : 300;
  const int repeats = argc > 5 ? std::atoi(argv[5]) : 5;
  const Eigen::Vector3d size(0.04, 0.02, 0.012);
  const models::HexMesh mesh = models::make_box_hex_mesh(nx, ny, nz, size);
  engine::solid::SolidMaterial mat;
  mat.youngs_modulus = 685e6;
  mat.poisson = 0.47;
  mat.density = 935.0;
  std::vector<uint8_t> fix(mesh.nodes.size(), 0);
  for (size_t n = 0; n < mesh.nodes.size(); ++n)
    if (mesh.nodes[n].z() == 0.0) fix[n] = engine::solid::kFixAll;
  std::printf("bench_solid: %d elements, %zu nodes, %d steps, median of %d\n", nx * ny * nz,
              mesh.nodes.size(), steps, repeats);
  double rate[3] = {0, 0, 0};
  for (int threads : {1, 2}) {
    engine::solid::SolidOptions options;
    options.threads = threads;
    const engine::solid::SolidModel model =
        engine::solid::make_solid_model(mesh.nodes, mesh.elements, mat, options, fix);
    std::vector<double> seconds;
    for (int r = 0; r < repeats; ++r) {
      engine::solid::SolidState state = engine::solid::make_solid_state(model);
      engine::solid::SolidData data = engine::solid::make_solid_data(model);
      for (size_t n = 0; n < mesh.nodes.size(); ++n)
        if (mesh.nodes[n].z() == size.z()) data.external_force[n] = Eigen::Vector3d(0.1, 0, -1.0);
      const auto t0 = std::chrono::steady_clock::now();
      for (int s = 0; s < steps; ++s) {
        if (engine::solid::step_solid(model, state, data, 0.7 * model.dt_critical) !=
            engine::solid::SolidStatus::kOk) {
          std::fprintf(stderr, "bench_solid: step %d failed\n", s);
          return 1;
        }
      }
      seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(seconds.begin(), seconds.end());
    const double median = seconds[seconds.size() / 2];
    rate[threads] = static_cast<double>(model.num_elements()) * steps / median;
    std::printf("threads %d: median %.4f s (min %.4f, max %.4f), %.2f M element-updates/s\n",
                threads, median, seconds.front(), seconds.back(), rate[threads] / 1e6);
  }
  std::printf("2-thread / 1-thread rate: %.2f\n", rate[2] / rate[1]);
  return 0;
}
