// Engine benchmark (not part of ctest): time per gait cycle at three insert resolutions,
// nanoseconds per contact-element evaluation, and the CPU-time ratio of the explicit
// central-difference integrator to the SUNDIALS CVODE reference on the same model, with the
// RMS difference of their AP and IE traces. Every figure is the median of --repeats runs on one
// thread; run it on a quiet machine in a Release build:
//
//   build/tools/bench_engine [--repeats 5] [--cycles 1]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <numbers>
#include <string>
#include <vector>

#include "engine/simulate.h"
#include "models/build_model.h"

namespace {

using namespace kneesim;

double cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Timing {
  double seconds_per_cycle = 0;  // CPU, median
  double ns_per_evaluation = 0;
  double evaluations_per_step = 0;
  long steps_per_cycle = 0;
  int elements = 0;
  std::vector<engine::Frame> frames;
};

// settles one cycle (not timed), then times `cycles` cycles, `repeats` times
Timing time_cycles(const engine::Model& model, int cycles, int repeats) {
  Timing t;
  std::vector<double> per_cycle, per_eval;
  for (int r = 0; r < repeats; ++r) {
    engine::State state = engine::make_initial_state(model);
    engine::Data data = engine::make_data(model);
    engine::RunOptions warm;
    warm.cycles = 1;
    engine::simulate(model, state, data, warm);
    const long eval0 = data.evaluations, step0 = state.step;
    engine::RunOptions o;
    o.cycles = cycles;
    const double c0 = cpu_seconds();
    const engine::RunResult res = engine::simulate(model, state, data, o);
    const double c1 = cpu_seconds();
    const long evals = data.evaluations - eval0;
    per_cycle.push_back((c1 - c0) / cycles);
    if (evals > 0) per_eval.push_back(1e9 * (c1 - c0) / evals);
    t.evaluations_per_step = static_cast<double>(evals) / std::max(1L, state.step - step0);
    t.frames = res.frames;
  }
  t.seconds_per_cycle = median(per_cycle);
  t.ns_per_evaluation = per_eval.empty() ? 0.0 : median(per_eval);
  t.steps_per_cycle = std::lround(model.period / model.dt);
  t.elements = model.insert.size();
  return t;
}

models::BuiltModel build(double edge_mm, const std::string& integrator) {
  std::vector<models::Override> o = {{"implant.edge_length_mm", std::to_string(edge_mm)},
                                     {"solver.integrator", "\"" + integrator + "\""}};
  return models::build_model(models::load_config("", o));
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 5, cycles = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--repeats")) repeats = std::max(1, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--cycles")) cycles = std::max(1, std::atoi(argv[i + 1]));
  }
  std::printf("kneesim engine benchmark: median of %d runs, %d timed cycle(s) each, 1 thread, "
              "CPU time\n\n", repeats, cycles);
  std::printf("| insert edge (mm) | elements | steps/cycle | evaluations/step | s/cycle | "
              "ns/evaluation |\n|---|---|---|---|---|---|\n");
  for (double edge : {2.0, 1.0, 0.7}) {
    const models::BuiltModel b = build(edge, "central_difference");
    const Timing t = time_cycles(b.model, cycles, repeats);
    std::printf("| %.1f | %d | %ld | %.0f | %.3f | %.1f |\n", edge, t.elements,
                t.steps_per_cycle, t.evaluations_per_step, t.seconds_per_cycle,
                t.ns_per_evaluation);
    std::fflush(stdout);
  }

  // explicit vs CVODE on the same (coarse) model
  const double edge = 2.0;
  const models::BuiltModel explicit_model = build(edge, "central_difference");
  const models::BuiltModel cvode_model = build(edge, "cvode");
  const int ref_repeats = std::max(1, repeats / 2);
  const Timing te = time_cycles(explicit_model.model, cycles, ref_repeats);
  const Timing tc = time_cycles(cvode_model.model, cycles, ref_repeats);
  double ap2 = 0, ie2 = 0;
  const size_t n = std::min(te.frames.size(), tc.frames.size());
  for (size_t i = 0; i < n; ++i) {
    ap2 += std::pow(1e3 * (te.frames[i].q[1][0] - tc.frames[i].q[1][0]), 2);
    ie2 += std::pow(180.0 / std::numbers::pi * (te.frames[i].q[1][4] - tc.frames[i].q[1][4]), 2);
  }
  std::printf("\n| integrator (edge %.1f mm) | s/cycle | ratio explicit/CVODE | AP RMS diff (mm) | "
              "IE RMS diff (deg) |\n|---|---|---|---|---|\n", edge);
  std::printf("| central difference | %.3f | %.3f | | |\n", te.seconds_per_cycle,
              te.seconds_per_cycle / tc.seconds_per_cycle);
  std::printf("| SUNDIALS CVODE (BDF) | %.3f | | %.3f | %.3f |\n", tc.seconds_per_cycle,
              n ? std::sqrt(ap2 / n) : 0.0, n ? std::sqrt(ie2 / n) : 0.0);
  return 0;
}
