#include "analysis/diagnosis/forces_case.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/errors.h"
#include "loads/iso14243/measured_loads.h"
#include "models/gait_assembly.h"

namespace kneesim::diagnosis {
namespace {

constexpr const char* kQuantity = "medial_force_N";
// the least axial force the rig is driven with, as a fraction of the record's peak [-]
constexpr double kMinAxialShare = 0.02;
// largest gap in gait phase the second cycle may have for the cycle-against-cycle rule [%]
constexpr double kMaxPhaseGap = 10.0;
// prior sd of each cell group's gain error and of each crosstalk fraction [-]: instrumented
// implants measure to 1-2 % of their calibration range including crosstalk (Bergmann et al.,
// J Biomech Eng 130(2):021009, 2008); --noise-param gain_crosstalk_sd
constexpr double kGainCrosstalkSd = 0.02;

std::string config_name(const models::Config& c) {
  return c.file.empty() ? std::string("built-in config") : c.file.string();
}

// a table waveform of the rig channels from samples at gait phases (sorted, distinct)
loads::Waveform phase_waveform(const loads::MeasuredLoads& L, const std::vector<std::string>& names,
                               const std::vector<std::pair<double, size_t>>& samples) {
  std::vector<double> pct;
  std::vector<std::vector<double>> cols(names.size());
  for (const auto& [p, i] : samples) {
    if (!pct.empty() && p <= pct.back()) continue;
    pct.push_back(p);
    for (size_t k = 0; k < names.size(); ++k) {
      cols[k].push_back(L.values[static_cast<size_t>(L.channel(names[k]))][i]);
    }
  }
  return loads::Waveform::from_table(names, pct, cols, L.source + " [other cycle]");
}

// the simulator's cycle of each row (by the row's group, the cycle's name)
std::vector<int> cycle_of_rows(const ForcesSimulator& sim, const MeasuredData& data) {
  std::vector<int> out;
  for (const auto& row : data.rows) {
    int k = 0;
    for (int i = 0; i < sim.cycles(); ++i) {
      if (sim.cycle(i).name == row.group) k = i;
    }
    out.push_back(k);
  }
  return out;
}

// Catmull-Rom interpolation through equally spaced values y at fractional index s
double catmull_rom(const std::vector<double>& y, double s) {
  const int n = static_cast<int>(y.size());
  const int j = std::clamp(static_cast<int>(std::floor(s)), 0, n - 2);
  const double t = s - j;
  auto at = [&](int i) {
    if (i < 0) return 2.0 * y[0] - y[1];
    if (i >= n) return 2.0 * y[static_cast<size_t>(n - 1)] - y[static_cast<size_t>(n - 2)];
    return y[static_cast<size_t>(i)];
  };
  const double p0 = at(j - 1), p1 = at(j), p2 = at(j + 1), p3 = at(j + 2);
  return 0.5 * (2.0 * p1 + (-p0 + p2) * t + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t * t +
                (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * t * t * t);
}

// The grid surrogate: per candidate, full simulations at equally spaced parameter values
// across its bounds, and the medial force of every row at each of them. Grid values whose
// simulation stopped (a torque the axial load cannot carry lifts a condyle off: runaway) limit
// the searched range to the contiguous runnable values around the spec's start.
struct Surrogate {
  std::shared_ptr<ForcesSimulator> sim;
  std::shared_ptr<const MeasuredData> measured;
  std::vector<int> cycle_of_row;
  std::vector<double> total;   // measured total per row [N]
  // the predicted medial force of a row: the rig's medial share there times the measured total
  double medial(const ForcesTrace& t, int row) const {
    return t.share(measured->rows[static_cast<size_t>(row)].x) * total[static_cast<size_t>(row)];
  }
  struct Table {
    std::vector<double> values;          // grid [param unit]
    int lo = 0, hi = 0;                  // runnable index range
    std::vector<std::vector<double>> y;  // rows x runnable grid values [N]
  };
  std::map<Effect, Table> tables;

  void build(const std::vector<Effect>& effects, int grid_points) {
    std::vector<ForcesSimulator::Key> keys;
    for (Effect e : effects) {
      const ParamSpec spec = effect_info(e).params.front();
      Table t;
      for (int g = 0; g < grid_points; ++g) {
        t.values.push_back(spec.lower + (spec.upper - spec.lower) * g / (grid_points - 1));
        for (int k = 0; k < sim->cycles(); ++k) keys.push_back({e, t.values.back(), k});
      }
      tables[e] = t;
    }
    sim->run_many(keys);
    for (Effect e : effects) {
      Table& t = tables[e];
      const ParamSpec spec = effect_info(e).params.front();
      const int n = static_cast<int>(t.values.size());
      std::vector<char> ok(static_cast<size_t>(n), 1);
      for (int g = 0; g < n; ++g) {
        for (int k = 0; k < sim->cycles(); ++k) ok[static_cast<size_t>(g)] &= sim->run(e, t.values[static_cast<size_t>(g)], k)->ok;
      }
      int g0 = 0;
      for (int g = 1; g < n; ++g) {
        if (std::abs(t.values[static_cast<size_t>(g)] - spec.initial) <
            std::abs(t.values[static_cast<size_t>(g0)] - spec.initial)) g0 = g;
      }
      t.lo = t.hi = g0;
      if (!ok[static_cast<size_t>(g0)]) {
        t.hi = g0 - 1;  // nothing runnable
        continue;
      }
      while (t.lo > 0 && ok[static_cast<size_t>(t.lo - 1)]) --t.lo;
      while (t.hi < n - 1 && ok[static_cast<size_t>(t.hi + 1)]) ++t.hi;
      t.y.assign(measured->rows.size(), {});
      for (int g = t.lo; g <= t.hi; ++g) {
        for (int k = 0; k < sim->cycles(); ++k) {
          const auto trace = sim->run(e, t.values[static_cast<size_t>(g)], k);
          for (size_t i = 0; i < measured->rows.size(); ++i) {
            if (cycle_of_row[i] == k) t.y[i].push_back(medial(*trace, static_cast<int>(i)));
          }
        }
      }
    }
  }
  // usable: at least three runnable grid values
  bool usable(Effect e) const { return tables.at(e).hi - tables.at(e).lo >= 2; }
  double lower(Effect e) const { return tables.at(e).values[static_cast<size_t>(tables.at(e).lo)]; }
  double upper(Effect e) const { return tables.at(e).values[static_cast<size_t>(tables.at(e).hi)]; }
  double at(Effect e, double v, int row) const {
    const Table& t = tables.at(e);
    const double h = t.values[1] - t.values[0];
    return catmull_rom(t.y[static_cast<size_t>(row)], (v - t.values[static_cast<size_t>(t.lo)]) / h);
  }
};

}  // namespace

ForcesMeasured read_forces_measured(const models::Config& config, const std::string& file) {
  if (config.measured_file.empty() && file.empty()) {
    throw InputError(config_name(config) + ": the forces diagnosis needs a [gait.measured] "
                     "section (the measured table, its window and channels; see "
                     "models/examples/jw_measured_loads.toml).");
  }
  loads::MeasuredLoadSpec spec = models::measured_load_spec(config);
  if (!file.empty()) spec.file = file;
  const loads::MeasuredLoads L = loads::read_measured_loads(spec);
  const int med = L.channel(kQuantity), tot = L.channel("axial_force_N");
  if (med < 0 || tot < 0) {
    throw InputError(spec.origin + ": the forces diagnosis compares medial_force_N, defined in "
                     "gait.measured.compare, under the measured axial_force_N of "
                     "gait.measured.channels (" + std::string(med < 0 ? "medial_force_N" : "axial_force_N") +
                     " is missing).");
  }
  std::vector<std::string> rig;
  for (const auto& n : L.names) {
    const auto& r = models::measured_rig_channels();
    if (std::find(r.begin(), r.end(), n) != r.end()) rig.push_back(n);
  }
  ForcesMeasured out;
  out.data.source = L.source;
  out.data.x_name = "gait_pct";
  const double ws = L.window_start, we = L.window_end, T = we - ws;
  const double period = L.percent ? config.period_s : T;
  // the rig's input: each rig channel low-pass filtered at the cutoff of Winter's residual
  // analysis (a table in gait percent has no sampling rate: taken as it is)
  loads::MeasuredLoads filtered = L;
  if (!L.percent && L.time.size() >= 20) {
    const double fs = static_cast<double>(L.time.size() - 1) / (L.time.back() - L.time.front());
    for (const auto& name : rig) {
      auto& v = filtered.values[static_cast<size_t>(L.channel(name))];
      const loads::CutoffChoice choice = loads::residual_analysis_cutoff(v, fs);
      if (choice.cutoff_Hz > 0.0) {
        v = loads::lowpass(v, fs, choice.cutoff_Hz);
        out.input_filter[name] = choice;
      }
    }
  }
  // a rig presses, it cannot pull: a measured total below kMinAxialShare of the record's peak
  // (the cells' offsets and noise in swing) is held there; below it the femur would lift off
  // and the simulation stop
  if (const int ax = filtered.channel("axial_force_N"); ax >= 0) {
    auto& v = filtered.values[static_cast<size_t>(ax)];
    const double floor = kMinAxialShare * *std::max_element(v.begin(), v.end());
    for (double& f : v) f = std::max(f, floor);
    out.axial_floor_N = floor;
  }
  const loads::Waveform w1 = loads::cycle_waveform(filtered, rig);
  out.cycles.push_back({"cycle 1", models::make_gait(config, &w1), period});
  auto add_row = [&](const std::string& group, double phase, size_t i) {
    out.data.rows.push_back({group, "", kQuantity, phase, L.values[static_cast<size_t>(med)][i],
                             L.line[i]});
    out.total_N.push_back(L.values[static_cast<size_t>(tot)][i]);
    out.time_s.push_back(L.time[i]);
  };
  for (size_t i = 0; i < L.time.size(); ++i) {
    if (L.time[i] >= ws && L.time[i] < we) add_row("cycle 1", 100.0 * (L.time[i] - ws) / T, i);
  }
  out.two_cycles = false;
  if (!L.percent) {
    // the other cycle: after the window, then the end of the previous cycle where it stops
    std::vector<std::pair<double, size_t>> other;
    double last_after = -1.0;
    for (size_t i = 0; i < L.time.size(); ++i) {
      if (L.time[i] >= we && L.time[i] < we + T) {
        other.push_back({100.0 * (L.time[i] - we) / T, i});
        last_after = other.back().first;
      }
    }
    for (size_t i = 0; i < L.time.size(); ++i) {
      const double p = 100.0 * (L.time[i] - (ws - T)) / T;
      if (L.time[i] < ws && L.time[i] >= ws - T && p > last_after) other.push_back({p, i});
    }
    std::sort(other.begin(), other.end());
    double gap = other.empty() ? 100.0 : other.front().first + 100.0 - other.back().first;
    for (size_t i = 1; i < other.size(); ++i) gap = std::max(gap, other[i].first - other[i - 1].first);
    if (other.size() >= 8 && gap <= kMaxPhaseGap) {
      out.two_cycles = true;
      const loads::Waveform w2 = phase_waveform(filtered, rig, other);
      out.cycles.push_back({"cycle 2", models::make_gait(config, &w2), period});
      for (const auto& [p, i] : other) add_row("cycle 2", p, i);
    }
  }
  return out;
}

DiagnosisCase make_forces_case(const ForcesMeasured& m, std::shared_ptr<ForcesSimulator> sim,
                               const ForcesCaseOptions& options) {
  DiagnosisCase c;
  c.name = "forces";
  c.measured = m.data;
  const models::Config& cfg = sim->config();
  c.baseline_model =
      "force-controlled rig of " + (cfg.file.empty() ? std::string("the built-in config") : cfg.file.string()) +
      " as configured (rig " + cfg.rig_preset + ", tibial VV axis " +
      std::to_string(cfg.tibia_pivot_medial_mm).substr(0, 4) + " mm medial, no VV torque), "
      "driven by each cycle's measured axial force and flexion, low-pass filtered (Winter's "
      "residual analysis); medial force = the medial share of the condyles' normal forces x "
      "the measured total";
  c.noise_model = NoiseModel::per_quantity;
  // the error model: correlated in time over the record, the cells' offset and drift, and
  // their gain and crosstalk under the instrument's calibration accuracy
  c.series_key.assign(c.measured.rows.size(), "record");
  c.series_x = m.time_s;
  c.series_unit = m.two_cycles || !m.time_s.empty() ? "s" : "gait_pct";
  c.error_model.correlation = Correlation::ou;
  {
    double t_mid = 0.0;
    for (double t : m.time_s) t_mid += t / static_cast<double>(m.time_s.size());
    const std::vector<double> time = m.time_s, total = m.total_N;
    auto rows_column = [](const std::vector<int>& rows, auto f) {
      Eigen::VectorXd v(static_cast<Eigen::Index>(rows.size()));
      for (size_t i = 0; i < rows.size(); ++i) v[static_cast<Eigen::Index>(i)] = f(i, rows[i]);
      return v;
    };
    c.error_model.nuisance = {
        {"offset_N", "offset of the medial reading (the cells' zero) [N]", 0.0, "",
         [rows_column](const std::vector<int>& rows, const Eigen::VectorXd&) {
           return rows_column(rows, [](size_t, int) { return 1.0; });
         }},
        {"drift_N_per_s", "linear drift of that offset over the record [N/s]", 0.0, "",
         [rows_column, time, t_mid](const std::vector<int>& rows, const Eigen::VectorXd&) {
           return rows_column(rows, [&](size_t, int r) { return time[static_cast<size_t>(r)] - t_mid; });
         }},
        // the cells' gain and crosstalk as they reach the residual medial - share x total:
        // the medial reading m and the total t are read from the same cells, so with true
        // forces M = s T and L = (1 - s) T, medial gains 1 + g_m, lateral 1 + g_l, crosstalk
        // c_l of the lateral cells into the medial reading and c_m of the medial into the
        // lateral, m - s t = s (1 - s) T (g_m - g_l) + c_l (1 - s)^2 T - c_m s^2 T to first
        // order: a gain common to all cells cancels in the share, as it does in the
        // trivial predictor (s from the prediction: pred / total)
        {"gain_difference", "gain of the medial cells minus that of the lateral cells, per unit "
                            "of s (1 - s) x the measured total [-]", kGainCrosstalkSd * std::sqrt(2.0),
         "gain_crosstalk_sd",
         [rows_column, total](const std::vector<int>& rows, const Eigen::VectorXd& pred) {
           return rows_column(rows, [&](size_t i, int r) {
             const double t = total[static_cast<size_t>(r)], p = pred[static_cast<Eigen::Index>(i)];
             return t != 0.0 ? p * (t - p) / t : 0.0;
           });
         },
         std::sqrt(2.0), false},
        {"crosstalk_lateral_to_medial", "crosstalk of the lateral cells into the medial reading, "
                                        "per unit of (1 - s)^2 x the measured total [-]",
         kGainCrosstalkSd, "gain_crosstalk_sd",
         [rows_column, total](const std::vector<int>& rows, const Eigen::VectorXd& pred) {
           return rows_column(rows, [&](size_t i, int r) {
             const double t = total[static_cast<size_t>(r)], p = pred[static_cast<Eigen::Index>(i)];
             return t != 0.0 ? (t - p) * (t - p) / t : 0.0;
           });
         },
         1.0, false},
        {"crosstalk_medial_to_lateral", "crosstalk of the medial cells into the lateral reading "
                                        "(it enters the total), per unit of -s^2 x the measured "
                                        "total [-]",
         kGainCrosstalkSd, "gain_crosstalk_sd",
         [rows_column, total](const std::vector<int>& rows, const Eigen::VectorXd& pred) {
           return rows_column(rows, [&](size_t i, int r) {
             const double t = total[static_cast<size_t>(r)], p = pred[static_cast<Eigen::Index>(i)];
             return t != 0.0 ? -p * p / t : 0.0;
           });
         },
         1.0, false}};
  }
  auto sur = std::make_shared<Surrogate>();
  sur->sim = sim;
  sur->measured = std::make_shared<const MeasuredData>(c.measured);
  sur->total = m.total_N;
  sur->cycle_of_row = cycle_of_rows(*sim, c.measured);
  // every candidate's grid at once (the simulator runs them in parallel)
  sur->build(options.candidates, options.grid_points);
  for (Effect e : options.candidates) {
    const ParamSpec spec = effect_info(e).params.front();
    const std::string set = sim->equivalent_sets(e, 0.0);
    c.model_notes[e] = "forward: kneesim run CONFIG " + set.substr(0, set.find('=') + 1) + "VALUE";
    if (!sur->usable(e)) {
      c.model_notes[e] += "; not a candidate: fewer than three runnable grid values";
      continue;
    }
    c.candidates.push_back(e);
    if (sur->lower(e) > spec.lower || sur->upper(e) < spec.upper) {
      c.model_notes[e] += "; searched range limited to [" + std::to_string(sur->lower(e)).substr(0, 6) +
                          ", " + std::to_string(sur->upper(e)).substr(0, 6) +
                          "]: beyond it a condyle lifts off and the simulation stops";
    }
  }
  // the forward model's error realizations: at the midpoint between each two neighbouring
  // grid values of each candidate, a direct simulation minus the interpolated grid, where the
  // interpolation is worst (on the synthetic record 0.9-10.6 N RMS, the largest towards the
  // ends of the grids, against 1.1-1.9 N for a 2 deg alignment; forces effect shape)
  {
    std::vector<ForcesSimulator::Key> keys;
    std::vector<std::pair<Effect, double>> mids;
    for (Effect e : c.candidates) {
      const auto& t = sur->tables.at(e);
      for (int g = t.lo; g < t.hi; ++g) {
        mids.push_back({e, 0.5 * (t.values[static_cast<size_t>(g)] + t.values[static_cast<size_t>(g + 1)])});
        for (int k = 0; k < sim->cycles(); ++k) keys.push_back({e, mids.back().second, k});
      }
    }
    sim->run_many(keys);  // all midpoints at once (in parallel)
    for (const auto& [e, v] : mids) {
      Eigen::VectorXd r = simulated_medial(*sim, m, e, v);
      for (Eigen::Index i = 0; i < r.size(); ++i) r[i] -= sur->at(e, v, static_cast<int>(i));
      if (r.allFinite()) c.forward_error_draws.push_back(r);
    }
  }
  c.effect_params = [sur](Effect e) {
    auto specs = effect_info(e).params;
    if (sur->tables.count(e) && sur->usable(e)) {
      specs[0].lower = sur->lower(e);
      specs[0].upper = sur->upper(e);
      specs[0].initial = std::clamp(specs[0].initial, specs[0].lower, specs[0].upper);
      std::vector<double> starts;
      for (double v : specs[0].starts) {
        if (v > specs[0].lower && v < specs[0].upper) starts.push_back(v);
      }
      specs[0].starts = starts;
    }
    return specs;
  };
  c.predict = [sur](Effect e, const Eigen::VectorXd&, const Eigen::VectorXd& ep,
                    const std::vector<int>& idx) {
    Eigen::VectorXd v(static_cast<Eigen::Index>(idx.size()));
    for (size_t i = 0; i < idx.size(); ++i) {
      const int row = idx[i];
      if (e == Effect::none || ep.size() == 0) {
        const auto trace = sur->sim->run(Effect::none, 0.0, sur->cycle_of_row[static_cast<size_t>(row)]);
        v[static_cast<Eigen::Index>(i)] = trace->ok ? sur->medial(*trace, row) : NAN;
      } else {
        v[static_cast<Eigen::Index>(i)] = sur->at(e, ep[0], row);
      }
    }
    return v;
  };
  c.calibrate_baseline = [](const std::vector<int>&) { return Eigen::VectorXd(); };
  // the trivial predictor: the total force is the rig's input, so the flat line to beat is the
  // training rows' mean medial share (load-weighted) times each row's measured total
  c.trivial_model = "mean measured medial share of the training rows (load-weighted) x the "
                    "row's measured total force";
  c.trivial_predict = [total = m.total_N](const Eigen::VectorXd& y, const std::vector<int>& train,
                                          const std::vector<int>& idx) {
    double medial = 0.0, sum = 0.0;
    for (int i : train) {
      medial += y[i];
      sum += total[static_cast<size_t>(i)];
    }
    const double share = sum > 0.0 ? medial / sum : 0.5;
    Eigen::VectorXd p(static_cast<Eigen::Index>(idx.size()));
    for (size_t k = 0; k < idx.size(); ++k) p[static_cast<Eigen::Index>(k)] = share * total[static_cast<size_t>(idx[k])];
    return p;
  };

  if (m.two_cycles) {
    c.split_rule = "cycle against cycle (fit on cycle 1, predict cycle 2; fit on cycle 2, "
                   "predict cycle 1)";
    Fold a{"cycle 1 -> cycle 2", {}, {}}, b{"cycle 2 -> cycle 1", {}, {}};
    for (size_t i = 0; i < c.measured.rows.size(); ++i) {
      const bool first = c.measured.rows[i].group == "cycle 1";
      (first ? a.train : a.test).push_back(static_cast<int>(i));
      (first ? b.test : b.train).push_back(static_cast<int>(i));
    }
    c.folds = {a, b};
  } else {
    c.split_rule = "interleaved gait-phase blocks of 10 % (fit on the even blocks, predict the "
                   "odd ones, and back)";
    Fold a{"even -> odd blocks", {}, {}}, b{"odd -> even blocks", {}, {}};
    for (size_t i = 0; i < c.measured.rows.size(); ++i) {
      const bool even = static_cast<int>(std::floor(c.measured.rows[i].x / 10.0)) % 2 == 0;
      (even ? a.train : a.test).push_back(static_cast<int>(i));
      (even ? b.test : b.train).push_back(static_cast<int>(i));
    }
    c.folds = {a, b};
  }
  c.curves = [sim](Effect e, const Eigen::VectorXd&, const Eigen::VectorXd& ep) {
    std::vector<CurvePoint> out;
    const double value = ep.size() > 0 ? ep[0] : 0.0;
    for (int k = 0; k < sim->cycles(); ++k) {
      const auto trace = sim->run(ep.size() > 0 ? e : Effect::none, value, k);
      for (size_t i = 0; trace->ok && i < trace->gait_pct.size(); ++i) {
        out.push_back({sim->cycle(k).name, kQuantity, trace->gait_pct[i], trace->medial_N[i]});
      }
    }
    return out;
  };
  return c;
}

Eigen::VectorXd simulated_medial(ForcesSimulator& sim, const ForcesMeasured& measured,
                                 Effect effect, double value) {
  const std::vector<int> cycle = cycle_of_rows(sim, measured.data);
  std::vector<ForcesSimulator::Key> keys;
  for (int k = 0; k < sim.cycles(); ++k) keys.push_back({effect, value, k});
  sim.run_many(keys);
  std::vector<std::shared_ptr<const ForcesTrace>> traces;
  for (int k = 0; k < sim.cycles(); ++k) traces.push_back(sim.run(effect, value, k));
  Eigen::VectorXd p(static_cast<Eigen::Index>(measured.data.rows.size()));
  for (size_t i = 0; i < measured.data.rows.size(); ++i) {
    const ForcesTrace& t = *traces[static_cast<size_t>(cycle[i])];
    p[static_cast<Eigen::Index>(i)] =
        t.ok ? t.share(measured.data.rows[i].x) * measured.total_N[i] : NAN;
  }
  return p;
}

}  // namespace kneesim::diagnosis
