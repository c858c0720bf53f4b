// Engine benchmark (not part of ctest): time per gait cycle at three insert resolutions,
// nanoseconds per contact-element evaluation, and the CPU-time ratio of the explicit
// central-difference integrator to the SUNDIALS CVODE reference on the same model, with the
// RMS difference of their AP and IE traces. Then the figures of docs/performance.md: the
// distance field's build time and memory, dense (the layout before issue 13) against bricked
// sampling of the same points of a gait cycle in the same run (a ratio that survives a busy
// machine), the disk cache's write and checked read of the field against its build, and
// hardware counters per evaluation where the CPU exposes them (a VM often does
// not: docs/performance.md has the callgrind counts). Every figure is the median of --repeats
// runs on one thread; run it on a quiet machine in a Release build:
//
//   build/tools/bench_engine [--repeats 5] [--cycles 1]
//
// With --deformable it times instead one gait cycle of the deformable insert (1.15 mm
// elements: 10 080, the size of issue 30's figure) from rest, wall clock, on 1 and 2 threads
// alternately, on an idle machine and with one core kept busy by a spinning child process
// (busy_core.h), and prints issue 30's rows: 2 threads within 10 s idle, and never slower
// than 1 thread with a core busy. Both thread counts give the same bits, which it checks.
//
//   build/tools/bench_engine --deformable [--repeats 3]
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <linux/perf_event.h>
#include <sys/ioctl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "busy_core.h"
#include "engine/simulate.h"
#include "models/build_model.h"
#include "models/distance_field_disk.h"

namespace {

using namespace kneesim;

double cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double wall_seconds() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
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

// the dense x-fastest layout of the field before issue 13, rebuilt node by node from the
// bricked field, with the sampling code of that time: the "before" of the layout table
struct DenseField {
  Eigen::Vector3d origin;
  double spacing = 0, band = 0;
  Eigen::Vector3i dims;
  std::vector<float> phi;
  explicit DenseField(const engine::SignedDistanceField& f)
      : origin(f.origin), spacing(f.spacing), band(f.band), dims(f.dims) {
    phi.resize(static_cast<size_t>(dims.x()) * dims.y() * dims.z());
    size_t n = 0;
    for (int k = 0; k < dims.z(); ++k)
      for (int j = 0; j < dims.y(); ++j)
        for (int i = 0; i < dims.x(); ++i) phi[n++] = f.node(i, j, k);
  }
  double sample(const Eigen::Vector3d& p_F) const {
    const Eigen::Vector3d g = (p_F - origin) / spacing;
    const double fx = std::floor(g.x()), fy = std::floor(g.y()), fz = std::floor(g.z());
    const int i = static_cast<int>(fx), j = static_cast<int>(fy), k = static_cast<int>(fz);
    if (i < 0 || j < 0 || k < 0 || i >= dims.x() - 1 || j >= dims.y() - 1 || k >= dims.z() - 1)
      return band;
    const double tx = g.x() - fx, ty = g.y() - fy, tz = g.z() - fz;
    const long sx = 1, sy = dims.x(), sz = static_cast<long>(dims.x()) * dims.y();
    const long base = i + sy * j + sz * k;
    const double c000 = phi[base], c100 = phi[base + sx];
    const double c010 = phi[base + sy], c110 = phi[base + sx + sy];
    const double c001 = phi[base + sz], c101 = phi[base + sx + sz];
    const double c011 = phi[base + sy + sz], c111 = phi[base + sx + sy + sz];
    const double c00 = c000 + tx * (c100 - c000), c10 = c010 + tx * (c110 - c010);
    const double c01 = c001 + tx * (c101 - c001), c11 = c011 + tx * (c111 - c011);
    const double c0 = c00 + ty * (c10 - c00), c1 = c01 + ty * (c11 - c01);
    return c0 + tz * (c1 - c0);
  }
};

// the bricked field sampled at grid coordinates as the contact loop does: with the SSE2 pairs
// of engine/sdf.h (round 3), or with round 2's scalar code, copied here as DenseField copies
// the layout before: the "before" of the interpolation row, and a check that both give the
// same bits
struct GridSampler {
  engine::FieldSampler s;
  Eigen::Vector3d origin;
  double spacing;
  bool scalar;
  GridSampler(const engine::SignedDistanceField& f, bool scalar_code)
      : s(f.sampler()), origin(f.origin), spacing(f.spacing), scalar(scalar_code) {}
  double sample(const Eigen::Vector3d& p_F) const {
    const Eigen::Vector3d g = (p_F - origin) / spacing;
    return scalar ? sample_scalar(g) : s.sample_grid(g);
  }
  [[gnu::noinline]] double sample_scalar(const Eigen::Vector3d& g) const {
    if (!(g.x() >= 0.0 && g.y() >= 0.0 && g.z() >= 0.0 && g.x() < s.limit[0] &&
          g.y() < s.limit[1] && g.z() < s.limit[2])) {
      return s.band;
    }
    const int i = static_cast<int>(g.x()), j = static_cast<int>(g.y()),
              k = static_cast<int>(g.z());
    const engine::BrickAxis ax = s.axis[0][i], ay = s.axis[1][j], az = s.axis[2][k];
    const int32_t brick = s.brick_of[ax.brick + ay.brick + az.brick];
    if (brick < 0) return brick == engine::kBrickOutside ? s.outside : s.inside;
    const double tx = g.x() - i, ty = g.y() - j, tz = g.z() - k;
    constexpr long sx = 1, sy = engine::kBrickNodes, sz = sy * sy;
    const float* phi =
        s.values + static_cast<long>(brick) * engine::kBrickSize + (ax.node + ay.node + az.node);
    const double c000 = phi[0], c100 = phi[sx];
    const double c010 = phi[sy], c110 = phi[sx + sy];
    const double c001 = phi[sz], c101 = phi[sx + sz];
    const double c011 = phi[sy + sz], c111 = phi[sx + sy + sz];
    const double c00 = c000 + tx * (c100 - c000), c10 = c010 + tx * (c110 - c010);
    const double c01 = c001 + tx * (c101 - c001), c11 = c011 + tx * (c111 - c011);
    const double c0 = c00 + ty * (c10 - c00), c1 = c01 + ty * (c11 - c01);
    return c0 + tz * (c1 - c0);
  }
};

// the points (F frame) at which a gait cycle samples the fine field, in evaluation order
std::vector<Eigen::Vector3d> record_sample_points(const engine::Model& model) {
  std::vector<Eigen::Vector3d> points;
  engine::State state = engine::make_initial_state(model);
  engine::Data data = engine::make_data(model);
  engine::RunOptions o;
  o.cycles = 1;
  o.observer = [&](const engine::Model& m, const engine::State&, const engine::Data& d) {
    const Eigen::Isometry3d X_FT = d.X_WF.inverse() * d.X_WT;
    for (int e : d.due) points.push_back(X_FT * m.insert.centroid_T[e]);
  };
  engine::simulate(model, state, data, o);
  return points;
}

template <class Field>
double ns_per_sample(const Field& field, const std::vector<Eigen::Vector3d>& points,
                     double& checksum) {
  const double c0 = cpu_seconds();
  double sum = 0;
  for (const auto& p : points) sum += field.sample(p);
  const double c1 = cpu_seconds();
  checksum = sum;
  return 1e9 * (c1 - c0) / std::max<size_t>(1, points.size());
}

// hardware counters of this thread (instructions, cycles, cache misses); absent in many VMs
struct Counters {
  int fd[3] = {-1, -1, -1};
  Counters() {
    const unsigned long configs[3] = {PERF_COUNT_HW_INSTRUCTIONS, PERF_COUNT_HW_CPU_CYCLES,
                                      PERF_COUNT_HW_CACHE_MISSES};
    for (int i = 0; i < 3; ++i) {
      perf_event_attr a{};
      a.size = sizeof a;
      a.type = PERF_TYPE_HARDWARE;
      a.config = configs[i];
      a.disabled = 1;
      a.exclude_kernel = 1;
      a.exclude_hv = 1;
      fd[i] = static_cast<int>(syscall(SYS_perf_event_open, &a, 0, -1, -1, 0));
    }
  }
  ~Counters() {
    for (int f : fd)
      if (f >= 0) close(f);
  }
  bool available() const { return fd[0] >= 0 && fd[1] >= 0; }
  void start() {
    for (int f : fd)
      if (f >= 0) {
        ioctl(f, PERF_EVENT_IOC_RESET, 0);
        ioctl(f, PERF_EVENT_IOC_ENABLE, 0);
      }
  }
  std::array<long long, 3> stop() {
    std::array<long long, 3> v{-1, -1, -1};
    for (int i = 0; i < 3; ++i)
      if (fd[i] >= 0) {
        ioctl(fd[i], PERF_EVENT_IOC_DISABLE, 0);
        if (read(fd[i], &v[i], sizeof v[i]) != sizeof v[i]) v[i] = -1;
      }
    return v;
  }
};

models::BuiltModel build(double edge_mm, const std::string& integrator) {
  std::vector<models::Override> o = {{"implant.edge_length_mm", std::to_string(edge_mm)},
                                     {"solver.integrator", "\"" + integrator + "\""}};
  return models::build_model(models::load_config("", o));
}

// --deformable: one gait cycle from rest, wall seconds, per thread count (1, 2), alternating
struct CycleRuns {
  std::vector<double> wall;
  std::vector<engine::Frame> frames;  // of the last run
};

std::vector<CycleRuns> time_deformable_cycles(const std::vector<models::BuiltModel>& built,
                                              int repeats) {
  std::vector<CycleRuns> runs(built.size());
  for (int r = 0; r < repeats; ++r) {
    for (size_t k = 0; k < built.size(); ++k) {
      const engine::Model& model = built[k].model;
      engine::State state = engine::make_initial_state(model);
      engine::Data data = engine::make_data(model);
      engine::RunOptions o;
      o.cycles = 1;
      const double w0 = wall_seconds();
      engine::RunResult res = engine::simulate(model, state, data, o);
      runs[k].wall.push_back(wall_seconds() - w0);
      if (res.status != engine::StepStatus::kOk) {
        std::fprintf(stderr, "bench_engine: the deformable cycle stopped: %s\n",
                     engine::to_string(res.status));
        std::exit(1);
      }
      runs[k].frames = std::move(res.frames);
    }
  }
  return runs;
}

int bench_deformable(int repeats) {
  const int threads[] = {1, 2};
  std::vector<models::BuiltModel> built;
  for (int t : threads) {
    built.push_back(models::build_model(models::load_config(
        "", {{"insert", "\"deformable\""},
             {"deformable.element_size_mm", "1.15"},
             {"solver.threads", std::to_string(t)}})));
  }
  std::printf("kneesim deformable gait cycle: %d elements, one cycle from rest, wall seconds, "
              "median (min-max) of %d runs per thread count, alternating\n",
              built[0].model.insert_solid.num_elements(), repeats);
  std::printf("\n| condition | 1 thread (s) | 2 threads (s) | 2 threads / 1 thread, speed | same "
              "bits |\n|---|---|---|---|---|\n");
  double idle2 = 0, busy_ratio = 0;
  for (const bool busy : {false, true}) {
    const pid_t spinner = busy ? bench::start_busy_core("bench_engine") : 0;
    const std::vector<CycleRuns> runs = time_deformable_cycles(built, repeats);
    if (busy) bench::stop_busy_core(spinner);
    const double m1 = median(runs[0].wall), m2 = median(runs[1].wall);
    bool same = runs[0].frames.size() == runs[1].frames.size();
    for (size_t i = 0; same && i < runs[0].frames.size(); ++i) {
      same = runs[0].frames[i].q == runs[1].frames[i].q;
    }
    const auto [lo1, hi1] = std::minmax_element(runs[0].wall.begin(), runs[0].wall.end());
    const auto [lo2, hi2] = std::minmax_element(runs[1].wall.begin(), runs[1].wall.end());
    std::printf("| %s | %.2f (%.2f-%.2f) | %.2f (%.2f-%.2f) | %.2f | %s |\n",
                busy ? "one core busy (spinning child)" : "idle", m1, *lo1, *hi1, m2, *lo2, *hi2,
                m1 / m2, same ? "yes" : "NO");
    std::fflush(stdout);
    if (busy) {
      busy_ratio = m1 / m2;
    } else {
      idle2 = m2;
    }
  }
  std::printf("\n| acceptance (issue 30) | measured | asked |\n|---|---|---|\n");
  std::printf("| one cycle of about 10 000 elements on 2 threads, idle (s) | %.2f | <= 10 |\n",
              idle2);
  std::printf("| 2 threads / 1 thread, speed, one core busy | %.2f | >= 0.9 (never slower) |\n",
              busy_ratio);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 0, cycles = 1;  // repeats: 5, or 3 with --deformable (a cycle takes 10-20 s)
  bool deformable = false;
  for (int i = 1; i < argc; ++i) {
    const bool value = i + 1 < argc;
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) {
      std::printf("usage: bench_engine [--repeats N] [--cycles N] | --deformable [--repeats N]\n"
                  "  rigid insert (default): s/cycle and ns/evaluation at three resolutions, "
                  "explicit vs CVODE, the distance field's figures; median of N runs (5)\n"
                  "  --deformable: one 10 080-element deformable gait cycle on 1 and 2 threads, "
                  "idle and with a core busy; median of N runs (3)\n");
      return 0;
    }
    if (!std::strcmp(argv[i], "--deformable")) {
      deformable = true;
    } else if (!std::strcmp(argv[i], "--repeats") && value) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--cycles") && value) {
      cycles = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "bench_engine: unknown option or missing value: %s\nusage: "
                   "bench_engine [--repeats N] [--cycles N] | --deformable [--repeats N]\n",
                   argv[i]);
      return 2;
    }
  }
  if (deformable) return bench_deformable(repeats > 0 ? repeats : 3);
  if (repeats == 0) repeats = 5;
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
  std::fflush(stdout);

  // the distance field of the default model (1 mm edge): build time and memory
  const models::BuiltModel def = build(1.0, "central_difference");
  const engine::SignedDistanceField& field = def.model.femur_sdf;
  std::vector<double> build_s;
  for (int r = 0; r < std::max(1, repeats / 2); ++r) {
    const double c0 = cpu_seconds();
    const engine::SignedDistanceField f = engine::make_signed_distance_field(
        def.implant.femur.vertices, def.implant.femur.triangles, field.spacing, field.band);
    build_s.push_back(cpu_seconds() - c0);
  }
  const double nodes = static_cast<double>(field.dims.prod());
  // the disk cache (models/distance_field_disk.h): writing the field's file, and reading it
  // back with every check, against building it
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("kneesim-bench-" + std::to_string(getpid())) /
      models::field_file_name(def.implant.femur.vertices, def.implant.femur.triangles,
                              field.spacing, field.band);
  std::vector<double> write_s, read_s;
  for (int r = 0; r < std::max(1, repeats / 2); ++r) {
    const double w0 = wall_seconds();
    models::write_field_file(file, def.implant.femur.vertices, def.implant.femur.triangles,
                             field);
    const double w1 = wall_seconds();
    const auto read = models::read_field_file(file, def.implant.femur.vertices,
                                              def.implant.femur.triangles, field.spacing,
                                              field.band);
    const double w2 = wall_seconds();
    if (!read) std::printf("(the field file did not read back)\n");
    write_s.push_back(w1 - w0);
    read_s.push_back(w2 - w1);
  }
  const auto file_bytes = std::filesystem::file_size(file);
  std::filesystem::remove_all(file.parent_path());
  std::printf("\n| femoral field (edge 1.0 mm) | nodes | dense MB | bricks stored / all | "
              "bricked MB | build s (CPU, 1 thread) | file MB | write s (wall) | read s (wall, "
              "checked) |\n|---|---|---|---|---|---|---|---|---|\n");
  std::printf("| spacing %.2f mm, band %.2f mm | %.0f | %.1f | %d / %d | %.1f | %.3f | %.1f | "
              "%.3f | %.3f |\n",
              1e3 * field.spacing, 1e3 * field.band, nodes, 4e-6 * nodes, field.stored_bricks(),
              field.bricks.prod(), 1e-6 * field.bytes(), median(build_s), 1e-6 * file_bytes,
              median(write_s), median(read_s));
  std::fflush(stdout);

  // before/after: the same points of a gait cycle sampled in the dense layout and the bricked
  const std::vector<Eigen::Vector3d> points = record_sample_points(def.model);
  const DenseField dense(field);
  std::vector<double> t_dense, t_brick;
  double sum_dense = 0, sum_brick = 0;
  for (int r = 0; r < repeats; ++r) {
    t_dense.push_back(ns_per_sample(dense, points, sum_dense));
    t_brick.push_back(ns_per_sample(field, points, sum_brick));
  }
  std::printf("\n| field layout, %zu samples of a gait cycle | ns/sample | ratio to dense | "
              "sum of samples (m) |\n|---|---|---|---|\n", points.size());
  std::printf("| dense x-fastest (before) | %.1f | 1 | %.9e |\n", median(t_dense), sum_dense);
  std::printf("| bricked 8^3 (after) | %.1f | %.2f | %.9e |\n", median(t_brick),
              median(t_brick) / median(t_dense), sum_brick);
  std::fflush(stdout);

  // round 3: the same points at grid coordinates, round 2's scalar interpolation against the
  // SSE2 pairs (the sample inlines into the contact loop, where it saves more: no call)
  const GridSampler scalar(field, true), pairs(field, false);
  std::vector<double> t_scalar, t_pairs;
  double sum_scalar = 0, sum_pairs = 0;
  for (int r = 0; r < repeats; ++r) {
    t_scalar.push_back(ns_per_sample(scalar, points, sum_scalar));
    t_pairs.push_back(ns_per_sample(pairs, points, sum_pairs));
  }
  std::printf("\n| bricked field at grid coordinates | ns/sample | ratio to scalar | sum of samples "
              "(m) |\n|---|---|---|---|\n");
  std::printf("| scalar interpolation (round 2) | %.1f | 1 | %.17g |\n", median(t_scalar),
              sum_scalar);
  std::printf("| SSE2 pairs (round 3) | %.1f | %.2f | %.17g (%s) |\n", median(t_pairs),
              median(t_pairs) / median(t_scalar), sum_pairs,
              sum_pairs == sum_scalar ? "same bits" : "DIFFERENT");
  std::fflush(stdout);

  // hardware counters per evaluation over one cycle of the default model
  Counters counters;
  std::printf("\n| counters per evaluation (edge 1.0 mm, 1 cycle) | instructions | cycles | "
              "cache misses |\n|---|---|---|---|\n");
  if (!counters.available()) {
    std::printf("| not available: this CPU or VM exposes no hardware counters "
                "(docs/performance.md: callgrind) | | | |\n");
    return 0;
  }
  engine::State state = engine::make_initial_state(def.model);
  engine::Data data = engine::make_data(def.model);
  engine::RunOptions o;
  o.cycles = 1;
  engine::simulate(def.model, state, data, o);
  const long e0 = data.evaluations;
  counters.start();
  engine::simulate(def.model, state, data, o);
  const auto v = counters.stop();
  const double evals = static_cast<double>(std::max(1L, data.evaluations - e0));
  std::printf("| step loop | %.1f | %.1f | %.3f |\n", v[0] / evals, v[1] / evals,
              v[2] >= 0 ? v[2] / evals : -1.0);
  return 0;
}
