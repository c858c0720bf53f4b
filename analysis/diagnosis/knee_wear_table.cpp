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
#include "wear/wear_loop.h"

namespace kneesim::diagnosis {
namespace {

constexpr double kLnPMin = 9.2103;   // ln(0.01 MPa / 1 Pa)
constexpr double kLnPMax = 19.519;            // ln(300 MPa / 1 Pa)

int bin_of(double lnp) {
  const double f = (lnp - kLnPMin) / (kLnPMax - kLnPMin);
  return std::clamp(static_cast<int>(f * KneeWearTable::kBins), 0, KneeWearTable::kBins - 1);
}

}  // namespace

KneeWearTable::KneeWearTable(const std::string& name, const models::Config& config,
                             const KneeGeometryPath& path)
    : name_(name) {
  const auto t0 = std::chrono::steady_clock::now();
  const models::BuiltModel built = models::build_model(config);
  friction_ = built.model.contact.friction;
  sarkar_ = wear::sarkar_factor(friction_);
  law_ = wear::make_wear_law(config.wear, built);
  if (!(law_.wear_factor > 0.0)) {
    throw std::runtime_error("condition '" + name + "': the insert material has no wear factor "
                             "(material.wear_factor_mm3_per_Nmm = 0); the diagnosis fits k");
  }
  period_ = built.model.period;
  states_.push_back(record(built.model, 0.0));

  // pristine figures: work, work-weighted geometric mean pressure and mean cross-shear
  const KneeCycleRecord& r0 = states_.front();
  double lnp_sum = 0.0, cs_sum = 0.0;
  for (Eigen::Index i = 0; i < r0.area.size(); ++i) {
    for (int b = 0; b < kBins; ++b) {
      const double w = r0.area[i] * r0.pds(i, b);
      work_ += w;
      lnp_sum += w * r0.lnp(i, b);
      cs_sum += w * r0.cross_shear[i];
    }
  }
  mean_pressure_ = work_ > 0.0 ? std::exp(lnp_sum / work_) : 0.0;
  mean_cross_shear_ = work_ > 0.0 ? cs_sum / work_ : 0.0;

  // the geometry path: the condition's wear loop under the config's law at k_ref, one
  // recorded cycle per update; running-in and incubation weight the cycles, not the sites, so
  // their geometry at a worn volume is Archard's (and the cycle counts below stay exact)
  KneeWearParams at_ref;
  at_ref.k = path.k_ref;
  wear::WearOptions o;
  o.law = loop_law(at_ref);
  if (o.law.law == wear::WearLaw::kRunningIn || o.law.law == wear::WearLaw::kIncubation) {
    o.law.law = wear::WearLaw::kArchard;
  }
  const double per_cycle = path.k_ref * r0.area.dot(r0.law_rate);  // the law's [m^3/cycle]
  if (path.states > 0 && path.target_volume > 0.0 && per_cycle > 0.0) {
    const double total = path.target_volume / per_cycle;
    long done = 0;
    for (int j = 1; j <= path.states; ++j) {
      const long upto = std::max(done + 1, std::lround(total * std::pow(double(j) / path.states, 1.5)));
      o.schedule.push_back(upto - done);
      done = upto;
    }
    o.total_cycles = done;
    std::vector<models::TriMesh> worn;
    std::vector<double> volumes;
    o.on_insert = [&worn](const models::TriMesh& insert) { worn.push_back(insert); };
    const wear::WearResult w = wear::run_wear(built, o);
    if (w.status != engine::StepStatus::kOk) {
      throw std::runtime_error("condition '" + name + "': the wear loop of the geometry path "
                               "stopped: " + w.message);
    }
    for (size_t u = 0; u < worn.size(); ++u) {
      engine::Model m = built.model;
      m.insert = models::make_worn_insert_surface(built, worn[u]);
      states_.push_back(record(m, w.records[u + 1].volume_depth));
    }
  }
  seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

KneeCycleRecord KneeWearTable::record(const engine::Model& model_in, double volume) const {
  engine::Model model = model_in;
  const int n = model.insert.size();
  KneeCycleRecord rec;
  rec.volume = volume;
  // observer: binned p ds per element, the frictional-work tensor (WearAccumulator), and the
  // largest elastic penetration
  Eigen::MatrixXd pds, lnp_w;
  wear::WearLawParams law;
  law.law = wear::WearLaw::kArchard;
  law.wear_factor = 1.0;
  law.friction = friction_;
  wear::WearAccumulator acc(n, law);
  wear::WearAccumulator law_acc(n, law_);  // the config's own law, as `kneesim wear` runs it
  // a worn insert conforms and stiffens the contact: when the stability monitor trips, the
  // step is halved (a whole number of steps per cycle), as the wear loop does
  for (int attempt = 0;; ++attempt) {
    pds = Eigen::MatrixXd::Zero(n, kBins);
    lnp_w = Eigen::MatrixXd::Zero(n, kBins);
    acc = wear::WearAccumulator(n, law);
    law_acc = wear::WearAccumulator(n, law_);
    rec.max_penetration = 0.0;
    engine::RunOptions ro;
    ro.cycles = 2;  // one settling cycle, then the observed one
    ro.observer = [&](const engine::Model& m, const engine::State& s, const engine::Data& d) {
      acc.observe(m, s, d);  // called for the last cycle only
      if (law_.law != wear::WearLaw::kArchard) law_acc.observe(m, s, d);
      for (int e : d.in_contact) {
        const double p = d.pressure[e];
        const double ds = d.slip_speed[e] * m.dt;
        if (p <= 0.0 || ds <= 0.0) continue;
        const double lp = std::log(p);
        const int b = bin_of(lp);
        pds(e, b) += p * ds;
        lnp_w(e, b) += p * ds * lp;
      }
      rec.max_penetration = std::max(rec.max_penetration, d.contact.max_penetration);
    };
    engine::State state = engine::make_initial_state(model);
    engine::Data data = engine::make_data(model);
    const engine::RunResult run = engine::simulate(model, state, data, ro);
    if (run.status == engine::StepStatus::kUnstableStep && attempt < 3) {
      model.dt = model.period / std::ceil(2.0 * model.period / model.dt);
      continue;
    }
    if (run.status != engine::StepStatus::kOk) {
      throw std::runtime_error("condition '" + name_ + "': the simulation stopped at t = " +
                               std::to_string(run.failed_at) + " s (" +
                               engine::to_string(run.status) + ")");
    }
    break;
  }

  // keep the elements that were in contact
  const std::vector<double> cs_all = acc.cross_shear_ratio();
  // the config law's depth per cycle per unit of the material's k (contact_area: C / k)
  std::vector<double> law_all;
  if (law_.law != wear::WearLaw::kArchard) {
    law_all = law_acc.potential_per_cycle();
    const double scale = wear::law_coefficient(law_) / law_.wear_factor;
    for (double& d : law_all) d *= scale;
  }
  std::vector<int> kept;
  for (int e = 0; e < n; ++e) {
    // the area law wears an element in contact that does not slide under pressure: keep it
    if (pds.row(e).sum() > 0.0 || (!law_all.empty() && law_all[static_cast<size_t>(e)] > 0.0))
      kept.push_back(e);
  }
  const auto m = static_cast<Eigen::Index>(kept.size());
  rec.area.resize(m);
  rec.cross_shear.resize(m);
  rec.law_rate.resize(m);
  rec.pds.resize(m, kBins);
  rec.lnp.resize(m, kBins);
  for (Eigen::Index i = 0; i < m; ++i) {
    const int e = kept[static_cast<size_t>(i)];
    rec.area[i] = model.insert.area[e];
    rec.cross_shear[i] = cs_all[static_cast<size_t>(e)];
    if (!law_all.empty()) rec.law_rate[i] = law_all[static_cast<size_t>(e)];
    for (int b = 0; b < kBins; ++b) {
      rec.pds(i, b) = pds(e, b);
      rec.lnp(i, b) = pds(e, b) > 0.0 ? lnp_w(e, b) / pds(e, b) : 0.0;
    }
  }

  if (law_all.empty()) rec.law_rate = sarkar_ * rec.pds.rowwise().sum();  // archard
  // vertex depth = sum over the vertex's elements of A_e / 3 d_e, over the vertex area
  const std::vector<double> varea = wear::vertex_areas(model.insert);
  std::vector<Eigen::Triplet<double>> trip;
  for (Eigen::Index i = 0; i < m; ++i) {
    const int e = kept[static_cast<size_t>(i)];
    for (int k = 0; k < 3; ++k) {
      const int v = model.insert.triangles[e][k];
      if (varea[static_cast<size_t>(v)] > 0.0) {
        trip.emplace_back(v, static_cast<int>(i), rec.area[i] / 3.0 / varea[static_cast<size_t>(v)]);
      }
    }
  }
  rec.spread.resize(static_cast<Eigen::Index>(varea.size()), m);
  rec.spread.setFromTriplets(trip.begin(), trip.end());
  return rec;
}

wear::WearLawParams KneeWearTable::loop_law(const KneeWearParams& p) const {
  wear::WearLawParams law;
  law.friction = friction_;
  law.wear_factor = p.k;
  switch (p.effect) {
    case Effect::pressure_dependent_wear:
      law.law = wear::WearLaw::kPressureDependent;
      law.alpha = p.pressure_exponent;
      law.p_ref = p.reference_pressure;
      break;
    case Effect::cross_shear:
      law.law = wear::WearLaw::kCrossShear;
      law.beta = p.cross_shear_gain;
      break;
    case Effect::running_in:
      law.law = wear::WearLaw::kRunningIn;
      law.running_in_excess = p.running_in_excess;
      law.running_in_cycles = p.running_in_cycles;
      break;
    case Effect::incubation:
      law.law = wear::WearLaw::kIncubation;
      law.incubation_cycles = p.incubation_cycles;
      break;
    case Effect::none:
    case Effect::creep:
    case Effect::friction:
    case Effect::restraint:
    case Effect::load_convention:
    case Effect::load_line:
    case Effect::vv_moment:
    case Effect::vv_alignment:
      // the baseline: the config's law, its coefficient per unit of the material's k
      law = law_;
      wear::set_law_coefficient(law, wear::law_coefficient(law_) * p.k / law_.wear_factor);
      law.wear_factor = p.k;
      law.creep = false;
      break;
  }
  return law;
}

Eigen::VectorXd KneeWearTable::element_depth_rate(const KneeCycleRecord& r,
                                                  const KneeWearParams& p) const {
  // the baseline is the config's own law (Archard unless [wear] law says otherwise); the
  // effects extend Archard, as the effect library defines them
  if (p.effect == Effect::none) return r.law_rate;
  Eigen::VectorXd d;
  if (p.effect == Effect::pressure_dependent_wear) {
    const double ln_ref = std::log(p.reference_pressure);
    d = (r.pds.array() * (-p.pressure_exponent * (r.lnp.array() - ln_ref)).exp())
            .rowwise()
            .sum()
            .matrix();
  } else {
    d = r.pds.rowwise().sum();
  }
  if (p.effect == Effect::cross_shear) {
    d.array() *= 1.0 + p.cross_shear_gain * r.cross_shear.array();
  }
  return sarkar_ * d;
}

double KneeWearTable::effective_cycles(const KneeWearParams& p, double cycles) const {
  if (p.effect == Effect::none) return wear::effective_cycles(law_, 0.0, cycles);  // config's law
  wear::WearLawParams law;
  law.law = p.effect == Effect::running_in   ? wear::WearLaw::kRunningIn
            : p.effect == Effect::incubation ? wear::WearLaw::kIncubation
                                             : wear::WearLaw::kArchard;
  law.running_in_excess = p.running_in_excess;
  law.running_in_cycles = p.running_in_cycles;
  law.incubation_cycles = p.incubation_cycles;
  return wear::effective_cycles(law, 0.0, cycles);
}

KneeWearTable::Rates KneeWearTable::rates(const KneeWearParams& p) const {
  Rates r;
  const auto n_states = static_cast<Eigen::Index>(states_.size());
  r.volume.resize(n_states);
  for (Eigen::Index s = 0; s < n_states; ++s) {
    const KneeCycleRecord& rec = states_[static_cast<size_t>(s)];
    const Eigen::VectorXd d = element_depth_rate(rec, p);
    const Eigen::VectorXd vd = rec.spread * d;
    r.volume[s] = p.k * rec.area.dot(d);
    if (s == 0) r.max_depth = vd.size() > 0 ? p.k * vd.maxCoeff() : 0.0;
    if (n_states > 1) {
      if (s == 0) r.vertex.resize(vd.size(), n_states);
      r.vertex.col(s) = p.k * vd;
    }
  }
  return r;
}

namespace {

// cycles to go from V_a to V_b when the rate is linear in V between r_a and r_b [cycles]
double segment_cycles(double dv, double r_a, double r_b) {
  const double q = r_b / r_a - 1.0;
  if (std::abs(q) < 1e-9) return dv / r_a;
  return dv * std::log1p(q) / (r_b - r_a);
}

// volume gained after n cycles from V_a with rate r_a and slope m = dr/dV [m^3]
double segment_volume(double n, double r_a, double m) {
  const double x = m * n;
  return std::abs(x) < 1e-9 ? r_a * n : r_a * std::expm1(x) / m;
}

// integral over the first n cycles of (V - V_a) [m^3 cycles]
double segment_volume_integral(double n, double r_a, double m) {
  const double x = m * n;
  if (std::abs(x) < 1e-6) return r_a * n * n * (0.5 + x / 6.0);
  return r_a / m * (std::expm1(x) / m - n);
}

}  // namespace

Eigen::VectorXd KneeWearTable::path_depth(const Rates& r, double cycles) const {
  // walk the states: on each segment the vertex rate is linear in V, so its integral over
  // cycles is vd_a n + (vd_b - vd_a) / dV * integral (V - V_a) dN; beyond the last state (or a
  // degenerate segment) the reached state's rates hold
  Eigen::VectorXd depth = Eigen::VectorXd::Zero(r.vertex.rows());
  double left = cycles;
  Eigen::Index s = 0;
  for (; s + 1 < r.volume.size(); ++s) {
    const double dv = state_volume(static_cast<int>(s + 1)) - state_volume(static_cast<int>(s));
    const double r_a = r.volume[s], r_b = r.volume[s + 1];
    if (!(dv > 0.0) || !(r_a > 0.0) || !(r_b > 0.0)) break;
    const double m = (r_b - r_a) / dv;
    const double n = std::min(left, segment_cycles(dv, r_a, r_b));
    depth += r.vertex.col(s) * n +
             (r.vertex.col(s + 1) - r.vertex.col(s)) * (segment_volume_integral(n, r_a, m) / dv);
    left -= n;
    if (left <= 0.0) return depth;
  }
  return depth + r.vertex.col(s) * left;
}

double KneeWearTable::volume(const KneeWearParams& p, const Rates& r, double cycles) const {
  const double n_eff = effective_cycles(p, cycles);
  if (r.volume.size() == 1) return r.volume[0] * n_eff;
  double v = 0.0, left = n_eff;
  for (Eigen::Index s = 0; s + 1 < r.volume.size(); ++s) {
    const double dv = state_volume(static_cast<int>(s + 1)) - state_volume(static_cast<int>(s));
    const double r_a = r.volume[s], r_b = r.volume[s + 1];
    if (!(dv > 0.0) || !(r_a > 0.0) || !(r_b > 0.0)) return v + r_a * left;
    const double n = segment_cycles(dv, r_a, r_b);
    if (left <= n) return v + segment_volume(left, r_a, (r_b - r_a) / dv);
    v += dv;
    left -= n;
  }
  return v + r.volume[r.volume.size() - 1] * left;
}

double KneeWearTable::max_depth(const KneeWearParams& p, const Rates& r, double cycles) const {
  const double n_eff = effective_cycles(p, cycles);
  double depth = r.volume.size() == 1 ? r.max_depth * n_eff : path_depth(r, n_eff).maxCoeff();
  if (p.effect == Effect::creep) {
    depth += p.creep_ratio * max_penetration() *
             (1.0 - std::exp(-cycles * period_ / p.creep_time));
  }
  return depth;
}

}  // namespace kneesim::diagnosis
