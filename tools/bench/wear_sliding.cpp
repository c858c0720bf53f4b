// Sliding-work diagnostics of one gait cycle (issue 11: why the deformable insert wears more
// than the rigid one). Not part of ctest. For the config given by --set overrides it simulates
// one settling cycle and one observed cycle and integrates over the observed one:
//
//   impulse   = int F_n dt                      contact normal force, wear sites' pressures
//   work      = int sum_site f_n |v_s| dt       the sliding work the wear accumulation uses
//   slip      = work / impulse                  force-weighted mean slip speed
//   volume    = k sqrt(1 + 3 mu^2) work         Archard volume of the cycle
//
// and for the deformable insert the same work with other slip definitions, to split a
// difference into its factors:
//
//   body      |v_femur,t| at the node            the node held fixed in T (the rigid path's slip)
//   post      |v_node(n+1/2) - v_femur|_t        the node's velocity after the step
//   node      |v_node(n+1/2)|_t                  the node's own tangential motion in T
//   friction  int -f_t . (v_node(n+1/2) - v_femur) dt, the work friction actually dissipates
//
//   build/tools/wear_sliding [--set key=value ...]
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "engine/simulate.h"
#include "models/build_model.h"
#include "models/config.h"
#include "wear/archard.h"

namespace {

using namespace kneesim;

struct Totals {
  double impulse = 0, work = 0, work_body = 0, work_post = 0, work_node = 0, friction = 0;
  double time = 0;
  long steps = 0;
  Eigen::Vector3d cop = Eigen::Vector3d::Zero();  // force-weighted contact position, T [m]
  double x_pos = 0;  // force-weighted |z| (distance from the sagittal midplane) [m]
};
constexpr int kBins = 20;

Eigen::Vector3d tangential(const Eigen::Vector3d& v, const Eigen::Vector3d& n) {
  return v - v.dot(n) * n;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<models::Override> overrides;
  std::string trace_path;  // --trace FILE: carriage rates per step over gait 10-20 %
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--set")) overrides.push_back(models::parse_override(argv[i + 1]));
    if (!std::strcmp(argv[i], "--trace")) trace_path = argv[i + 1];
  }
  FILE* trace = trace_path.empty() ? nullptr : std::fopen(trace_path.c_str(), "w");
  if (trace) std::fprintf(trace, "t,fem0,fem1,fem2,fem3,fem4,fem5,tib0,tib1,tib2,tib3,tib4,tib5\n");
  const models::Config config = models::load_config("", overrides);
  const models::BuiltModel built = models::build_model(config);
  const engine::Model& model = built.model;
  const bool solid = !model.insert_solid.empty();
  engine::State state = engine::make_initial_state(model);
  engine::Data data = engine::make_data(model);
  Totals t;
  std::vector<Totals> bins(kBins);
  engine::RunOptions ro;
  ro.cycles = 2;
  ro.observer = [&](const engine::Model& m, const engine::State& s, const engine::Data& d) {
    const double dt = m.dt;
    t.time += dt;
    ++t.steps;
    Totals& b = bins[std::min(kBins - 1, static_cast<int>(d.gait_pct * kBins / 100.0))];
    b.time += dt;
    if (trace && d.gait_pct >= 10.0 && d.gait_pct < 20.0) {
      std::fprintf(trace, "%.7f", s.time);
      for (int c = 0; c < 2; ++c)
        for (int j = 0; j < 6; ++j) std::fprintf(trace, ",%.6g", s.carriages[c].rate[j]);
      std::fprintf(trace, "\n");
    }
    if (!solid) {
      for (int e : d.in_contact) {
        const double f = d.pressure[e] * m.insert.area[e];
        for (Totals* u : {&t, &b}) {
          u->impulse += f * dt;
          u->work += f * d.slip_speed[e] * dt;
          u->work_body += f * d.slip_speed[e] * dt;
          u->cop += f * dt * m.insert.centroid_T[e];
          u->x_pos += f * dt * std::abs(m.insert.centroid_T[e].z());
        }
      }
      return;
    }
    const auto& c = d.insert_contact;
    for (int i = 0; i < m.insert_contact.size(); ++i) {
      if (!(c.pressure[i] > 0.0)) continue;
      const int node = m.insert_contact.nodes[i];
      const double f = c.pressure[i] * m.insert_contact.area[i];
      const Eigen::Vector3d& n = d.insert_solid.friction_normal[node];
      const Eigen::Vector3d& vb = c.body_velocity[i];
      const Eigen::Vector3d& vn = s.insert_solid.velocity[node];
      const Eigen::Vector3d& x = s.insert_solid.position[node];
      for (Totals* u : {&t, &b}) {
        u->impulse += f * dt;
        u->work += f * c.slip_speed[i] * dt;
        u->work_body += f * tangential(vb, n).norm() * dt;
        u->work_post += f * tangential(vn - vb, n).norm() * dt;
        u->work_node += f * tangential(vn, n).norm() * dt;
        u->friction += -c.friction_force[i].dot(vn - vb) * dt;
        u->cop += f * dt * x;
        u->x_pos += f * dt * std::abs(x.z());
      }
    }
  };
  const engine::RunResult run = engine::simulate(model, state, data, ro);
  const double mu = config.friction_override >= 0 ? config.friction_override
                                                  : config.material.friction;
  const double k = config.material.wear_factor_mm3_per_Nmm * wear::kWearFactorSI;
  const double volume = k * wear::sarkar_factor(mu) * t.work;
  std::printf("insert %s, status %s, dt %.3g us, steps %ld (%.4g s)\n",
              solid ? "deformable" : "rigid", engine::to_string(run.status), model.dt * 1e6,
              t.steps, t.time);
  if (solid) {
    std::printf("insert mass %.4g kg physical, %.4g kg added by mass scaling\n",
                model.insert_solid.physical_mass, model.insert_solid.added_mass);
  }
  std::printf("impulse_Ns %.6g\nmean_force_N %.6g\n", t.impulse, t.impulse / t.time);
  std::printf("sliding_work_J %.6g\nmean_slip_mm_per_s %.6g\n", t.work, 1e3 * t.work / t.impulse);
  std::printf("volume_per_cycle_mm3 %.6g\nvolume_5Mc_mm3 %.6g\n", volume * 1e9, 5e6 * volume * 1e9);
  if (solid) {
    std::printf("work_body_J %.6g (mean slip %.6g mm/s)\n", t.work_body,
                1e3 * t.work_body / t.impulse);
    std::printf("work_post_J %.6g (mean slip %.6g mm/s)\n", t.work_post,
                1e3 * t.work_post / t.impulse);
    std::printf("work_node_J %.6g (mean node tangential speed %.6g mm/s)\n", t.work_node,
                1e3 * t.work_node / t.impulse);
    std::printf("friction_dissipation_J %.6g (mu * work %.6g)\n", t.friction, mu * t.work);
  }
  std::printf("gait_pct mean_force_N slip_mm_per_s body_slip_mm_per_s cop_x_mm |z|_mm\n");
  for (int i = 0; i < kBins; ++i) {
    const Totals& b = bins[i];
    const double F = b.impulse > 0 ? b.impulse : 1;
    std::printf("%5.1f %9.2f %8.3f %8.3f %7.3f %7.3f\n", 100.0 * i / kBins, b.impulse / b.time,
                1e3 * b.work / F, 1e3 * b.work_body / F, 1e3 * b.cop.x() / F, 1e3 * b.x_pos / F);
  }
  return run.status == engine::StepStatus::kOk ? 0 : 1;
}
