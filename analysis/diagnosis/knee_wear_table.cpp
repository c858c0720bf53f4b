#include "analysis/diagnosis/knee_wear_table.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "engine/simulate.h"
#include "models/build_model.h"
#include "wear/archard.h"
#include "wear/geometry_update.h"
#include "wear/wear_accumulator.h"

namespace kneesim::diagnosis {
namespace {

constexpr double kLnPMin = 9.2103;   // ln(0.01 MPa / 1 Pa)
constexpr double kLnPMax = 19.519;            // ln(300 MPa / 1 Pa)

int bin_of(double lnp) {
  const double f = (lnp - kLnPMin) / (kLnPMax - kLnPMin);
  return std::clamp(static_cast<int>(f * KneeWearTable::kBins), 0, KneeWearTable::kBins - 1);
}

}  // namespace

KneeWearTable::KneeWearTable(const std::string& name, const models::Config& config)
    : name_(name) {
  const auto t0 = std::chrono::steady_clock::now();
  const models::BuiltModel built = models::build_model(config);
  const engine::Model& model = built.model;
  const int n = model.insert.size();
  friction_ = model.contact.friction;
  sarkar_ = wear::sarkar_factor(friction_);
  period_ = model.period;

  // observer: binned p ds per element, the frictional-work tensor (WearAccumulator), and the
  // largest elastic penetration
  Eigen::MatrixXd pds = Eigen::MatrixXd::Zero(n, kBins), lnp_w = Eigen::MatrixXd::Zero(n, kBins);
  wear::WearLawParams law;
  law.law = wear::WearLaw::kArchard;
  law.wear_factor = 1.0;
  law.friction = friction_;
  wear::WearAccumulator acc(n, law);
  engine::RunOptions ro;
  ro.cycles = 2;  // one settling cycle, then the observed one
  ro.observer = [&](const engine::Model& m, const engine::State& s, const engine::Data& d) {
    acc.observe(m, s, d);
    for (int e : d.in_contact) {
      const double p = d.pressure[e];
      const double ds = d.slip_speed[e] * m.dt;
      if (p <= 0.0 || ds <= 0.0) continue;
      const double lp = std::log(p);
      const int b = bin_of(lp);
      pds(e, b) += p * ds;
      lnp_w(e, b) += p * ds * lp;
    }
    max_penetration_ = std::max(max_penetration_, d.contact.max_penetration);
  };
  engine::State state = engine::make_initial_state(model);
  engine::Data data = engine::make_data(model);
  const engine::RunResult run = engine::simulate(model, state, data, ro);
  if (run.status != engine::StepStatus::kOk) {
    throw std::runtime_error("condition '" + name + "': the simulation stopped at t = " +
                             std::to_string(run.failed_at) + " s (" +
                             engine::to_string(run.status) + ")");
  }

  // keep the elements that were in contact
  const std::vector<double> cs_all = acc.cross_shear_ratio();
  std::vector<int> kept;
  for (int e = 0; e < n; ++e) {
    if (pds.row(e).sum() > 0.0) kept.push_back(e);
  }
  const auto m = static_cast<Eigen::Index>(kept.size());
  area_.resize(m);
  cross_shear_.resize(m);
  pds_.resize(m, kBins);
  lnp_.resize(m, kBins);
  std::vector<int> column(static_cast<size_t>(n), -1);
  double lnp_sum = 0.0, cs_sum = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) {
    const int e = kept[static_cast<size_t>(i)];
    column[static_cast<size_t>(e)] = static_cast<int>(i);
    area_[i] = model.insert.area[e];
    cross_shear_[i] = cs_all[static_cast<size_t>(e)];
    for (int b = 0; b < kBins; ++b) {
      pds_(i, b) = pds(e, b);
      lnp_(i, b) = pds(e, b) > 0.0 ? lnp_w(e, b) / pds(e, b) : 0.0;
      work_ += area_[i] * pds(e, b);
      lnp_sum += area_[i] * lnp_w(e, b);
      cs_sum += area_[i] * pds(e, b) * cross_shear_[i];
    }
  }
  mean_pressure_ = work_ > 0.0 ? std::exp(lnp_sum / work_) : 0.0;
  mean_cross_shear_ = work_ > 0.0 ? cs_sum / work_ : 0.0;

  // vertex depth = sum over the vertex's elements of A_e / 3 d_e, over the vertex area
  const std::vector<double> varea = wear::vertex_areas(model.insert);
  std::vector<Eigen::Triplet<double>> trip;
  for (Eigen::Index i = 0; i < m; ++i) {
    const int e = kept[static_cast<size_t>(i)];
    for (int k = 0; k < 3; ++k) {
      const int v = model.insert.triangles[e][k];
      if (varea[static_cast<size_t>(v)] > 0.0) {
        trip.emplace_back(v, static_cast<int>(i), area_[i] / 3.0 / varea[static_cast<size_t>(v)]);
      }
    }
  }
  spread_.resize(static_cast<Eigen::Index>(varea.size()), m);
  spread_.setFromTriplets(trip.begin(), trip.end());
  seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Eigen::VectorXd KneeWearTable::element_depth_rate(const KneeWearParams& p) const {
  Eigen::VectorXd d;
  if (p.effect == Effect::pressure_dependent_wear) {
    const double ln_ref = std::log(p.reference_pressure);
    d = (pds_.array() * (-p.pressure_exponent * (lnp_.array() - ln_ref)).exp())
            .rowwise()
            .sum()
            .matrix();
  } else {
    d = pds_.rowwise().sum();
  }
  if (p.effect == Effect::cross_shear) {
    d.array() *= 1.0 + p.cross_shear_gain * cross_shear_.array();
  }
  return sarkar_ * d;
}

double KneeWearTable::effective_cycles(const KneeWearParams& p, double cycles) const {
  if (p.effect != Effect::running_in) return cycles;
  // integral of 1 + a exp(-N / N_r) from 0 to N (the block-on-ring running-in law)
  return cycles + p.running_in_excess * p.running_in_cycles *
                      (1.0 - std::exp(-cycles / p.running_in_cycles));
}

KneeWearTable::Rates KneeWearTable::rates(const KneeWearParams& p) const {
  const Eigen::VectorXd d = element_depth_rate(p);
  const Eigen::VectorXd vd = spread_ * d;
  return {p.k * area_.dot(d), vd.size() > 0 ? p.k * vd.maxCoeff() : 0.0};
}

double KneeWearTable::volume(const KneeWearParams& p, const Rates& r, double cycles) const {
  return r.volume * effective_cycles(p, cycles);
}

double KneeWearTable::max_depth(const KneeWearParams& p, const Rates& r, double cycles) const {
  double depth = r.max_depth * effective_cycles(p, cycles);
  if (p.effect == Effect::creep) {
    depth += p.creep_ratio * max_penetration_ * (1.0 - std::exp(-cycles * period_ / p.creep_time));
  }
  return depth;
}

}  // namespace kneesim::diagnosis
