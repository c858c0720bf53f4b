#include "wear/bor/bor_fe.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "engine/errors.h"
#include "engine/solid/solid_build.h"
#include "engine/solid/solid_step.h"
#include "engine/solid/surface_contact.h"
#include "models/hex_mesh.h"

namespace kneesim::bor {
namespace sol = engine::solid;
namespace {

std::string fmt(const char* f, double v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

void check_option(bool ok, const std::string& sentence) {
  if (!ok) throw InputError("command line: " + sentence);
}

// grid lines from a to b [m] with about `size` spacing, a and b included
std::vector<double> uniform_lines(double a, double b, double size) {
  const int n = std::max(1, static_cast<int>(std::ceil((b - a) / size - 1e-9)));
  std::vector<double> v(n + 1);
  for (int i = 0; i <= n; ++i) v[i] = a + (b - a) * i / n;
  v[n] = b;
  return v;
}

// the rigid ring: a cylinder of radius R about the z axis through (0, centre_y), its surface
// moving at omega x r. Its width enters through the contact set (the nodes whose reference
// position is under the ring, |z| <= w/2), not through the sample: a cut on the current z
// would switch an edge node's force on and off as it bulges sideways, a discontinuous
// potential that pumps energy into the explicit solve (measured: kinetic energy stuck at
// 40 % of the strain energy).
struct Ring {
  double radius = 0.0, omega = 0.0, centre_y = 0.0;
  sol::RigidSample operator()(const Eigen::Vector3d& p) const {
    sol::RigidSample s;
    const Eigen::Vector3d d(p.x(), p.y() - centre_y, 0.0);
    const double r = d.norm();
    s.phi = r - radius;
    s.normal = d / r;
    s.velocity = Eigen::Vector3d(-omega * d.y(), omega * d.x(), 0.0);
    return s;
  }
};

// the half block with everything that changes with its geometry
class FeBlock {
 public:
  FeBlock(const BorRig& rig, const BorFeOptions& o) : rig_(rig), o_(o) {
    const double half_w = 0.5 * rig.ring_width, half_b = 0.5 * rig.block_width;
    xs_ = models::make_graded_lines(-0.5 * rig.block_length, 0.5 * rig.block_length, 0.0,
                                    o.fine_half_width, o.element_size, o.growth);
    ys_ = models::make_graded_lines(-rig.block_height, 0.0, 0.0, o.fine_depth, o.element_size,
                                    o.growth);
    zs_ = uniform_lines(0.0, half_w, o.axial_element_size);
    if (half_b > half_w * (1.0 + 1e-9)) {
      const auto side = uniform_lines(half_w, half_b, 0.5 * o.axial_element_size);
      zs_.insert(zs_.end(), side.begin() + 1, side.end());
    }
    mesh_ = models::make_graded_box_hex_mesh(xs_, ys_, zs_);
    constraint_.assign(mesh_.nodes.size(), 0);
    for (size_t n = 0; n < mesh_.nodes.size(); ++n) {
      if (mesh_.nodes[n].z() == 0.0) constraint_[n] |= sol::kFixZ;  // symmetry plane
    }
    for (int n : mesh_.base_nodes) constraint_[n] = sol::kFixAll;
    for (size_t f = 0; f < mesh_.top_faces.size(); ++f) {
      double zc = 0.0;
      for (int n : mesh_.top_faces[f]) zc += 0.25 * mesh_.nodes[n].z();
      if (zc < half_w) {
        ring_faces_.push_back(mesh_.top_faces[f]);
        ring_face_element_.push_back(mesh_.top_face_element[f]);
      }
    }
    material_.kind = sol::SolidMaterialKind::kElastic;
    material_.youngs_modulus = rig.youngs_modulus;
    material_.poisson = rig.poisson_ratio;
    material_.density = o.density;
    // one stable step for every element: the largest element's
    sol::SolidOptions plain;
    const sol::SolidModel unscaled =
        sol::make_solid_model(mesh_.nodes, mesh_.elements, material_, plain, constraint_);
    for (const auto& ref : unscaled.reference) {
      target_dt_ = std::max(target_dt_, sol::calc_element_stable_step(ref, material_,
                                                                      material_.density));
    }
    reference_ = mesh_.nodes;
    build(reference_);
    // damping: critical for the block's lowest compression mode, omega = pi c / (2 h) with
    // the wave speed of the scaled mass
    const double volume = rig.block_length * rig.block_height * half_b;
    double mass = 0.0;
    for (double m : model_.nodal_mass) mass += m;
    const double c = std::sqrt(material_.dilatational_modulus() * volume / mass);
    info_.damping_alpha = o.damping_factor * 2.0 * M_PI * c / (2.0 * rig.block_height);
    model_.damping_alpha = info_.damping_alpha;
    state_ = sol::make_solid_state(model_);
    data_ = sol::make_solid_data(model_);
    wear_.assign(contact_.size(), 0.0);
    ring_.radius = rig.ring_radius;
    ring_.omega = rig.speed_rpm * 2.0 * M_PI / 60.0;
    ring_.centre_y = rig.ring_radius;  // touching
    info_.elements = model_.num_elements();
    info_.nodes = model_.num_nodes();
    info_.dt = 0.8 * model_.dt_critical;
  }

  const BorFeMeshInfo& info() const { return info_; }

  // dynamic relaxation of the current geometry under the load; returns the steps taken
  int relax(double load) {
    const double f_half = 0.5 * load, dt = info_.dt;
    const double c = 0.5 * dt * info_.damping_alpha;
    int good_checks = 0;
    for (int s = 1; s <= o_.max_relax_steps; ++s) {
      for (auto& f : data_.external_force) f.setZero();
      sol::apply_surface_contact(model_, contact_, state_, data_, out_, ring_);
      // friction: the sliding traction of the last solved state, a dead load here
      for (int i = 0; i < contact_.size(); ++i) {
        data_.external_force[contact_.nodes[i]] += friction_force_[i];
      }
      if (sol::step_solid(model_, state_, data_, dt) != sol::SolidStatus::kOk) {
        throw std::runtime_error("block-on-ring FE: element " +
                                 std::to_string(data_.inverted_element) +
                                 " of the block inverted during the contact solve");
      }
      const double reaction = -out_.total_force.y() - friction_y_;  // on the ring, upwards
      ring_velocity_ = ((1.0 - c) * ring_velocity_ + dt * (reaction - f_half) / ring_mass_) /
                       (1.0 + c);
      ring_.centre_y += dt * ring_velocity_;
      reaction_ = reaction;
      if (s % 20 != 0) continue;
      const bool balanced = std::abs(reaction - f_half) <= o_.force_tolerance * f_half;
      const bool still = data_.kinetic_energy + 0.5 * ring_mass_ * ring_velocity_ * ring_velocity_ <=
                         o_.kinetic_tolerance * data_.total_strain_energy;
      good_checks = (balanced && still) ? good_checks + 1 : 0;
      if (good_checks >= 3) return s;
    }
    throw std::runtime_error(
        "block-on-ring FE: the contact did not reach equilibrium within " +
        std::to_string(o_.max_relax_steps) + " relaxation steps (ring reaction " +
        fmt("%.4g", 2.0 * reaction_) + " N against the load " + fmt("%.4g", load) +
        " N); raise --fe-max-steps or coarsen the mesh");
  }

  // the sliding friction mu |f_n| along the ring surface's velocity at each node in contact,
  // from the solved state; returns the change against the friction used, relative to the
  // total friction force
  double update_friction() {
    double change = 0.0, total = 0.0;
    friction_y_ = 0.0;
    for (int i = 0; i < contact_.size(); ++i) {
      Eigen::Vector3d f = Eigen::Vector3d::Zero();
      if (out_.pressure[i] > 0.0) {
        const sol::RigidSample s = ring_(state_.position[contact_.nodes[i]]);
        const Eigen::Vector3d t = s.velocity - s.velocity.dot(s.normal) * s.normal;
        f = rig_.friction * out_.force[i].norm() * t.normalized();
      }
      change += (f - friction_force_[i]).norm();
      total += f.norm();
      friction_force_[i] = f;
      friction_y_ += f.y();
    }
    return total > 0.0 ? change / total : 0.0;
  }

  // the row of the current (solved) geometry
  BorFeRow measure(double cycles, double load, int steps) const {
    BorFeRow r;
    r.relax_steps = steps;
    r.contact_force = 2.0 * reaction_;
    r.peak_pressure = out_.peak_pressure;
    r.kinetic_ratio = data_.kinetic_energy / data_.total_strain_energy;
    r.row.cycles = cycles;
    r.row.volume = 2.0 * removed_volume();
    double depth = 0.0, wear_sum = 0.0;
    for (int i = 0; i < contact_.size(); ++i) {
      depth = std::max(depth, -reference_[contact_.nodes[i]].y());
      wear_sum += wear_[i] * wear_area_[i];
    }
    r.row.depth = depth;
    r.wear_sum_volume = 2.0 * wear_sum;
    const double area = 2.0 * out_.area;
    r.row.mean_pressure = area > 0.0 ? load / area : 0.0;
    // the centre row (z = 0): contact width between the midpoints to the first free nodes,
    // and the second moment of the vertical nodal forces about their centroid
    const int ny = mesh_.ny;
    double left = INFINITY, right = -INFINITY, f = 0.0, fx = 0.0, fx2 = 0.0;
    for (int i = 0; i <= mesh_.nx; ++i) {
      const int idx = contact_index_[mesh_.node(i, ny, 0)];
      if (idx < 0 || !(out_.pressure[idx] > 0.0)) continue;
      const double x = state_.position[mesh_.node(i, ny, 0)].x();
      const double lo = i > 0 ? 0.5 * (x + state_.position[mesh_.node(i - 1, ny, 0)].x()) : x;
      const double hi =
          i < mesh_.nx ? 0.5 * (x + state_.position[mesh_.node(i + 1, ny, 0)].x()) : x;
      left = std::min(left, lo);
      right = std::max(right, hi);
      const double fy = -out_.force[idx].y();
      r.centre_peak_pressure = std::max(r.centre_peak_pressure, out_.pressure[idx]);
      f += fy;
      fx += fy * x;
      fx2 += fy * x * x;
    }
    r.row.contact_width = right > left ? right - left : 0.0;
    r.centre_line_load = f / (0.5 * (zs_[1] - zs_[0]));
    if (f > 0.0) {
      const double mean = fx / f;
      r.hertz_half_width = 2.0 * std::sqrt(std::max(0.0, fx2 / f - mean * mean));
    }
    r.row.theta = std::asin(std::min(1.0, 0.5 * r.row.contact_width / rig_.ring_radius));
    return r;
  }

  // Archard over dN revolutions at the current pressures, then the new reference geometry
  void wear(double k, double cycles) {
    const double sliding = sliding_distance_per_cycle(rig_) * cycles;
    // nodal normals of the reference top surface under the ring (area-weighted)
    std::vector<Eigen::Vector3d> normal(contact_.size(), Eigen::Vector3d::Zero());
    for (const auto& q : ring_faces_) {
      const Eigen::Vector3d n =
          (reference_[q[2]] - reference_[q[0]]).cross(reference_[q[3]] - reference_[q[1]]);
      for (int a : q) normal[contact_index_[a]] += n;
    }
    std::vector<Eigen::Vector3d> next = reference_;
    const int stride = (mesh_.nx + 1) * (mesh_.ny + 1);
    double deepest = 0.0;
    for (int i = 0; i < contact_.size(); ++i) {
      // Archard on the node's force over its tributary area on the whole top surface (the
      // ring's edge nodes share faces beyond the ring, which their recession also lowers), so
      // that the worn volume is k S dN times the sum of the normal contact forces
      const double dh = k * out_.force[i].norm() / wear_area_[i] * sliding;
      if (!(dh > 0.0)) continue;
      wear_[i] += dh;
      deepest = std::max(deepest, dh);
      const int top = contact_.nodes[i];
      Eigen::Vector3d n = normal[i];
      if (constraint_[top] & sol::kFixZ) n.z() = 0.0;  // stays on the symmetry plane
      const Eigen::Vector3d d = -dh * n.normalized();
      const int ix = top % (mesh_.nx + 1), kz = top / stride;
      for (int j = 1; j <= mesh_.ny; ++j) {
        const double s = (ys_[j] - ys_[0]) / (ys_.back() - ys_[0]);
        next[mesh_.node(ix, j, kz)] += s * d;
      }
    }
    // the displacement field carries over to the new geometry; the ring follows the surface
    std::vector<Eigen::Vector3d> displacement(state_.position.size());
    for (size_t n = 0; n < displacement.size(); ++n) {
      displacement[n] = state_.position[n] - reference_[n];
    }
    reference_ = std::move(next);
    build(reference_);
    model_.damping_alpha = info_.damping_alpha;
    state_ = sol::make_solid_state(model_);
    for (size_t n = 0; n < displacement.size(); ++n) {
      state_.position[n] = reference_[n] + displacement[n];
    }
    ring_.centre_y -= deepest;
    ring_velocity_ = 0.0;
  }

 private:
  void build(const std::vector<Eigen::Vector3d>& nodes) {
    sol::SolidOptions options;
    options.mass_scaling_dt = target_dt_;
    options.threads = o_.threads;
    model_ = sol::make_solid_model(nodes, mesh_.elements, material_, options, constraint_);
    contact_ = sol::make_surface_contact(model_, ring_faces_, ring_face_element_, 0.0, 1e-3);
    if (friction_force_.empty()) friction_force_.assign(contact_.size(), Eigen::Vector3d::Zero());
    if (out_.pressure.empty()) out_ = sol::make_surface_contact_data(contact_);
    if (contact_index_.empty()) {
      contact_index_.assign(model_.num_nodes(), -1);
      for (int i = 0; i < contact_.size(); ++i) contact_index_[contact_.nodes[i]] = i;
    }
    wear_area_.assign(contact_.size(), 0.0);
    for (const auto& q : mesh_.top_faces) {
      const double area = 0.5 * (nodes[q[2]] - nodes[q[0]]).cross(nodes[q[3]] - nodes[q[1]]).norm();
      for (int a : q) {
        if (contact_index_[a] >= 0) wear_area_[contact_index_[a]] += 0.25 * area;
      }
    }
    ring_mass_ = 0.0;
    for (int n : contact_.nodes) ring_mass_ += model_.nodal_mass[n];
  }

  // the volume between the original top plane y = 0 and the top faces [m^3]: the integral of
  // -y over the faces' projection on the x-z plane, exact with 2 x 2 Gauss points (bilinear
  // faces)
  double removed_volume() const {
    static const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
    double v = 0.0;
    for (const auto& q : mesh_.top_faces) {
      const Eigen::Vector3d &p0 = reference_[q[0]], &p1 = reference_[q[1]],
                            &p2 = reference_[q[2]], &p3 = reference_[q[3]];
      for (double u : g)
        for (double w : g) {
          const Eigen::Vector3d pu = (1 - w) * (p1 - p0) + w * (p2 - p3);
          const Eigen::Vector3d pw = (1 - u) * (p3 - p0) + u * (p2 - p1);
          const double y = (1 - u) * (1 - w) * p0.y() + u * (1 - w) * p1.y() + u * w * p2.y() +
                           (1 - u) * w * p3.y();
          v += 0.25 * -y * (pu.z() * pw.x() - pu.x() * pw.z());
        }
    }
    return v;
  }

  BorRig rig_;
  BorFeOptions o_;
  std::vector<double> xs_, ys_, zs_;
  models::HexMesh mesh_;
  std::vector<uint8_t> constraint_;
  std::vector<std::array<int, 4>> ring_faces_;
  std::vector<int> ring_face_element_;
  sol::SolidMaterial material_;
  double target_dt_ = 0.0;
  std::vector<Eigen::Vector3d> reference_;  // the worn, stress-free geometry [m]
  sol::SolidModel model_;
  sol::SolidState state_;
  sol::SolidData data_;
  sol::SurfaceContact contact_;
  sol::SurfaceContactData out_;
  std::vector<int> contact_index_;  // node -> contact index, -1 off the ring's footprint
  std::vector<double> wear_;        // accumulated wear depth per contact node [m]
  std::vector<Eigen::Vector3d> friction_force_;  // sliding friction per contact node [N]
  std::vector<double> wear_area_;   // tributary area of each contact node on the whole top [m^2]
  Ring ring_;
  double ring_mass_ = 0.0, ring_velocity_ = 0.0, reaction_ = 0.0;
  double friction_y_ = 0.0;  // vertical sum of friction_force_ [N]
  BorFeMeshInfo info_;
};

}  // namespace

void check_bor_fe_options(const BorFeOptions& o, const BorRig& rig) {
  check_option(o.element_size >= 0.02e-3 && o.element_size <= 1e-3,
               "--fe-element-mm = " + fmt("%g", o.element_size * 1e3) +
                   " mm is outside the allowed range [0.02, 1] mm.");
  check_option(o.axial_element_size >= o.element_size && o.axial_element_size <= 0.5 * rig.ring_width,
               "--fe-axial-element-mm = " + fmt("%g", o.axial_element_size * 1e3) +
                   " mm is outside the allowed range [--fe-element-mm, half the ring width = " +
                   fmt("%g", 0.5e3 * rig.ring_width) + "] mm.");
  check_option(o.update_cycles >= 1.0 && std::floor(o.update_cycles) == o.update_cycles,
               "--update-every = " + fmt("%g", o.update_cycles) +
                   " must be a whole number of cycles >= 1.");
  check_option(o.max_relax_steps >= 100 && o.max_relax_steps <= 100000000,
               "--fe-max-steps = " + std::to_string(o.max_relax_steps) +
                   " is outside the allowed range [100, 1e8].");
  check_option(o.fine_half_width > 0.0 && o.fine_half_width < 0.5 * rig.block_length,
               "the fine zone half-length " + fmt("%g", o.fine_half_width * 1e3) +
                   " mm must lie inside the block (0, half the block length).");
  check_option(o.growth >= 1.0 && o.growth <= 2.0,
               "the mesh growth ratio " + fmt("%g", o.growth) + " is outside [1, 2].");
}

std::vector<BorFeRow> simulate_bor_fe(const BorRig& rig, double load, const BorWearParams& params,
                                      const std::vector<double>& cycles,
                                      const BorFeOptions& options, const BorFeProgress& progress) {
  check_rig(rig, "block-on-ring FE");
  check_bor_fe_options(options, rig);
  for (size_t i = 0; i < cycles.size(); ++i) {
    if (!(cycles[i] >= 0.0) || (i > 0 && cycles[i] < cycles[i - 1])) {
      throw std::invalid_argument("simulate_bor_fe needs cycle counts >= 0 in ascending order");
    }
  }
  FeBlock block(rig, options);
  // a geometry is solved with the friction of the last solved state as a dead load, then
  // again while the friction it leaves differs from the one it used by more than 1 %
  auto solve = [&] {
    int steps = 0;
    for (int pass = 0; pass < 10; ++pass) {
      steps += block.relax(load);
      if (block.update_friction() <= 0.01) return steps;
    }
    throw std::runtime_error("block-on-ring FE: the sliding friction did not settle in 10 passes");
  };
  std::vector<BorFeRow> rows;
  double n = 0.0;
  int steps = solve();
  for (double target : cycles) {
    while (n < target) {
      const double dn = std::min(options.update_cycles, target - n);
      block.wear(params.k, dn);
      n += dn;
      steps = solve();
      if (progress && n < target) progress(block.measure(n, load, steps), block.info());
    }
    rows.push_back(block.measure(n, load, steps));
    if (progress) progress(rows.back(), block.info());
  }
  return rows;
}

}  // namespace kneesim::bor
