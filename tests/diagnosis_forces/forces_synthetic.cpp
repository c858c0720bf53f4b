#include "tests/diagnosis_forces/forces_synthetic.h"

#include <cmath>
#include <numbers>
#include <random>
#include <sstream>

#include "analysis/diagnosis/forces_case.h"
#include "engine/io/source_tree.h"
#include "loads/iso14243/waveform.h"

namespace kneesim::test {
namespace {

using diagnosis::Effect;

constexpr double kRate = 100.0;    // samples per second
constexpr double kStart = 0.10;    // heel strike of cycle 1 [s]
constexpr double kPeriod = 1.0;    // [s]
constexpr double kEnd = 2.25;      // end of the record [s]
constexpr int kCells = 4;          // PM, AM, AL, PL

const char* kConfig = R"toml(
[implant]
edge_length_mm = 2.0
[gait.measured]
file = "clean.csv"
window = [0.10, 1.10]
channels = ["axial_force_N = PM_N + AM_N + AL_N + PL_N", "flexion_deg = flexion_deg"]
compare = ["medial_force_N = PM_N + AM_N"]
)toml";

struct Loads {
  std::vector<double> t, total, flexion, phase;
  std::vector<int> cycle;  // the clean simulation's cycle whose loads the sample carries
};

Loads clean_loads() {
  const auto w = loads::load_waveform(io::source_dir().string() + "/loads/iso14243/iso14243_1_approx.csv");
  const int ax = w.channel("axial_force_N"), fe = w.channel("flexion_deg");
  Loads l;
  for (int i = 0; i / kRate <= kEnd + 1e-9; ++i) {
    const double t = i / kRate;
    const double phase = std::fmod((t - kStart) / kPeriod + 10.0, 1.0) * 100.0;
    const bool second = t >= kStart + kPeriod;
    l.t.push_back(t);
    l.phase.push_back(phase);
    l.total.push_back(w.value(ax, phase) * (second ? 0.93 : 1.0));
    l.flexion.push_back(w.value(fe, phase) + (second ? 2.0 : 0.0) * std::sin(std::numbers::pi * phase / 100.0));
    l.cycle.push_back(second ? 1 : 0);
  }
  return l;
}

// anterior fraction of each compartment's force over the cycle (the contact migrates)
double anterior_medial(double phase) { return 0.5 + 0.15 * std::sin(2.0 * std::numbers::pi * (phase / 100.0 - 0.1)); }
double anterior_lateral(double phase) { return 0.5 + 0.12 * std::sin(2.0 * std::numbers::pi * (phase / 100.0 - 0.3)); }

std::string table(const Loads& l, const std::vector<std::array<double, kCells>>& cells) {
  std::ostringstream o;
  o.precision(10);
  o << "time_s,PM_N,AM_N,AL_N,PL_N,flexion_deg\n";
  for (size_t i = 0; i < l.t.size(); ++i) {
    o << l.t[i];
    for (double c : cells[i]) o << "," << c;
    o << "," << l.flexion[i] << "\n";
  }
  return o.str();
}

// an AR(1) series of stationary sd `sd` with correlation time `tau` [s]
std::vector<double> ar1(size_t n, double sd, double tau, std::mt19937_64& rng) {
  std::normal_distribution<double> z(0.0, 1.0);
  const double phi = std::exp(-1.0 / (kRate * tau));
  std::vector<double> x(n);
  double v = sd * z(rng);
  for (size_t i = 0; i < n; ++i) {
    x[i] = v;
    v = phi * v + sd * std::sqrt(1.0 - phi * phi) * z(rng);
  }
  return x;
}

// the instrument's errors added to the true cell forces
void add_noise(CellNoise kind, const Loads& l, std::vector<std::array<double, kCells>>& cells,
               std::mt19937_64& rng) {
  std::normal_distribution<double> z(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const size_t n = l.t.size();
  switch (kind) {
    case CellNoise::white_walk:
      for (int c = 0; c < kCells; ++c) {
        double walk = 0.0;
        for (size_t i = 0; i < n; ++i) {
          walk += 2.0 * z(rng);
          cells[i][static_cast<size_t>(c)] += 10.0 * z(rng) + walk;
        }
      }
      break;
    case CellNoise::resonant: {
      const double dt = 1.0 / kRate, theta = 2.0 * std::numbers::pi * 7.0 * dt;
      const double r = std::exp(-dt / 0.15);
      const double a1 = 2.0 * r * std::cos(theta), a2 = -r * r;
      for (int c = 0; c < kCells; ++c) {
        std::vector<double> x(n + 200, 0.0);
        for (size_t i = 2; i < x.size(); ++i) x[i] = a1 * x[i - 1] + a2 * x[i - 2] + z(rng);
        double ss = 0.0;
        for (size_t i = 200; i < x.size(); ++i) ss += x[i] * x[i];
        const double scale = 12.0 / std::sqrt(ss / static_cast<double>(n));
        const double offset = -15.0 + 30.0 * u(rng);
        for (size_t i = 0; i < n; ++i) cells[i][static_cast<size_t>(c)] += scale * x[i + 200] + offset;
      }
      break;
    }
    case CellNoise::crosstalk: {
      const double c1 = 0.03 + 0.03 * u(rng), c2 = 0.03 + 0.03 * u(rng);
      std::array<double, kCells> gain;
      for (double& g : gain) g = 1.0 + 0.02 * z(rng);
      for (size_t i = 0; i < n; ++i) {
        const auto f = cells[i];  // PM, AM, AL, PL
        cells[i][0] = gain[0] * (f[0] + c1 * f[2]);
        cells[i][2] = gain[2] * (f[2] + c1 * f[0]);
        cells[i][1] = gain[1] * (f[1] + c2 * f[3]);
        cells[i][3] = gain[3] * (f[3] + c2 * f[1]);
        for (double& v : cells[i]) v += 8.0 * z(rng);
      }
      break;
    }
    case CellNoise::pink:
      for (int c = 0; c < kCells; ++c) {
        for (double tau : {0.005, 0.02, 0.08, 0.32}) {
          const auto x = ar1(n, 7.0, tau, rng);
          for (size_t i = 0; i < n; ++i) cells[i][static_cast<size_t>(c)] += x[i];
        }
      }
      break;
    case CellNoise::harmonic:
      for (int c = 0; c < kCells; ++c) {
        for (int m = 0; m < 2; ++m) {
          const double f = 1.5 + 4.5 * u(rng), ph = 2.0 * std::numbers::pi * u(rng);
          for (size_t i = 0; i < n; ++i) {
            cells[i][static_cast<size_t>(c)] += 10.0 * std::sin(2.0 * std::numbers::pi * f * l.t[i] + ph);
          }
        }
        for (size_t i = 0; i < n; ++i) cells[i][static_cast<size_t>(c)] += 5.0 * z(rng);
      }
      break;
  }
}

}  // namespace

const char* cell_noise_name(CellNoise n) {
  switch (n) {
    case CellNoise::white_walk: return "white_walk";
    case CellNoise::resonant: return "resonant";
    case CellNoise::crosstalk: return "crosstalk";
    case CellNoise::pink: return "pink";
    case CellNoise::harmonic: return "harmonic";
  }
  return "";
}

const std::vector<CellNoise>& all_cell_noises() {
  static const std::vector<CellNoise> all = {CellNoise::white_walk, CellNoise::resonant,
                                             CellNoise::crosstalk, CellNoise::pink,
                                             CellNoise::harmonic};
  return all;
}

ForcesBench::ForcesBench() {
  const Loads l = clean_loads();
  std::vector<std::array<double, kCells>> cells(l.t.size());
  for (size_t i = 0; i < l.t.size(); ++i) {
    const double m = 0.6 * l.total[i], lat = l.total[i] - m;
    const double am = anterior_medial(l.phase[i]), al = anterior_lateral(l.phase[i]);
    cells[i] = {m * (1.0 - am), m * am, lat * al, lat * (1.0 - al)};
  }
  tmp_.write("clean.csv", table(l, cells));
  config_path_ = tmp_.write("synthetic.toml", kConfig).string();
  config_ = models::load_config(config_path_, {});
  clean_ = diagnosis::read_forces_measured(config_, "");
  clean_sim_ = std::make_shared<diagnosis::ForcesSimulator>(config_, clean_.cycles);
  clean_sim_->set_threads(2);
}

ForcesSet ForcesBench::make(Effect truth, double value, CellNoise kind, std::uint64_t seed,
                            double noise_scale) {
  const Loads l = clean_loads();
  std::vector<std::array<double, kCells>> cells(l.t.size());
  for (size_t i = 0; i < l.t.size(); ++i) {
    const auto trace = clean_sim_->run(truth, value, l.cycle[i]);
    const double share = trace->share(l.phase[i]);
    const double m = share * l.total[i], lat = l.total[i] - m;
    const double am = anterior_medial(l.phase[i]), al = anterior_lateral(l.phase[i]);
    cells[i] = {m * (1.0 - am), m * am, lat * al, lat * (1.0 - al)};
  }
  const auto true_cells = cells;
  std::mt19937_64 rng(seed);
  add_noise(kind, l, cells, rng);
  for (size_t i = 0; i < cells.size(); ++i) {
    for (int c = 0; c < kCells; ++c) {
      const auto k = static_cast<size_t>(c);
      cells[i][k] = true_cells[i][k] + noise_scale * (cells[i][k] - true_cells[i][k]);
    }
  }
  ForcesSet s;
  s.value = value;
  s.noise_scale = noise_scale;
  s.file = tmp_.write("set" + std::to_string(written_++) + ".csv", table(l, cells)).string();
  s.measured = diagnosis::read_forces_measured(config_, s.file);
  // the noise of the medial reading over the diagnosed rows
  double ss = 0.0;
  for (size_t r = 0; r < s.measured.data.rows.size(); ++r) {
    const double t = s.measured.time_s[r];
    const size_t i = static_cast<size_t>(std::lround(t * kRate));
    const double truth_m = true_cells[i][0] + true_cells[i][1];
    ss += std::pow(s.measured.data.rows[r].value - truth_m, 2);
  }
  s.noise_rms = std::sqrt(ss / static_cast<double>(s.measured.data.rows.size()));
  return s;
}

double ForcesBench::signal(Effect truth, double value) {
  auto& c = signal_cases_[truth];
  if (!c) {
    diagnosis::ForcesCaseOptions o;
    o.candidates = {truth};
    c = std::make_shared<diagnosis::DiagnosisCase>(diagnosis::make_forces_case(clean_, clean_sim_, o));
  }
  return diagnosis::identifiable_signal_rms(*c, truth, Eigen::VectorXd(),
                                            Eigen::VectorXd::Constant(1, value));
}

ForcesSet ForcesBench::make_at_ratio(Effect truth, double ratio, CellNoise kind,
                                     std::uint64_t seed) {
  std::mt19937_64 rng(seed ^ 0x5bd1e995u);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double value = 0.0, target = 0.0;
  if (truth == Effect::none) {
    target = signal(Effect::load_line, 2.5) / 1.2;  // the noise of a typical test set
  } else {
    const double hi = truth == Effect::vv_alignment ? 2.5 : 3.0;
    value = (u(rng) < 0.5 ? -1.0 : 1.0) * (1.0 + (hi - 1.0) * u(rng));
    target = signal(truth, value) / ratio;
  }
  const double unit_noise = make(Effect::none, 0.0, kind, seed).noise_rms;
  ForcesSet s = make(truth, value, kind, seed, target / unit_noise);
  s.signal_rms = truth == Effect::none ? 0.0 : signal(truth, value);
  return s;
}

diagnosis::ForcesDiagnosisReport ForcesBench::diagnose(const ForcesSet& s,
                                                       const diagnosis::DiagnosisOptions& options) {
  auto sim = std::make_shared<diagnosis::ForcesSimulator>(config_, s.measured.cycles);
  sim->set_threads(2);
  const diagnosis::DiagnosisCase c = diagnosis::make_forces_case(s.measured, sim);
  return diagnosis::diagnose_forces(c, *sim, s.measured.total_N, options);
}

}  // namespace kneesim::test
