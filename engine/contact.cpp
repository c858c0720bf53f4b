#include "engine/contact.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "engine/contact_law.h"
#include "engine/due_masks.h"
#include "engine/kinematics.h"
#include "engine/rig_coupling.h"
#include "engine/sdf_pairs.h"

namespace kneesim::engine {

void update_contact_schedule(const Model& model, Data& data) {
  if (!data.schedule_valid) {
    std::fill(data.recheck_at.begin(), data.recheck_at.end(), data.motion);
    data.X_FT_prev = data.X_WF.inverse() * data.X_WT;
    data.schedule_valid = true;
  } else {
    accumulate_contact_motion(model, data);
  }
  // the due list in ascending order from bit masks of 64 elements: only the due elements'
  // bits are visited
  const int n = model.insert.size();
  uint64_t* masks = data.due_mask.data();
  const long count = find_due_masks(data.recheck_at.data(), n, data.motion, masks);
  data.due.resize(count);  // capacity reserved (make_data); grows by a few entries at most
  int* due = data.due.data();
  for (int base = 0, w = 0; base < n; base += 64, ++w) {
    for (uint64_t mask = masks[w]; mask != 0; mask &= mask - 1) {
      *due++ = base + std::countr_zero(mask);
    }
  }
}

void accumulate_contact_motion(const Model& model, Data& data) {
  const Eigen::Isometry3d X_FT = data.X_WF.inverse() * data.X_WT;
  if (model.femur_radius > 0.0) {
    // the step's motion seen from the femur, D = X_FT(n+1) X_FT(n)^-1, moves a point at p_F by
    // at most angle(D) |p_F| + |t_D|; measured at |p_F| = femur_radius
    const Eigen::Isometry3d D = X_FT * data.X_FT_prev.inverse();
    const double angle = Eigen::AngleAxisd(D.linear()).angle();
    data.motion += D.translation().norm() + angle * model.femur_radius;
  } else {
    // no femoral radius known: bound by the insert's own extent
    const Eigen::Isometry3d delta = data.X_FT_prev.inverse() * X_FT;
    const double angle = Eigen::AngleAxisd(delta.linear()).angle();
    data.motion += delta.translation().norm() + angle * data.insert_radius;
  }
  data.X_FT_prev = X_FT;
}

namespace {

// a carriage's rigid motion this step: pivot velocity, angular velocity and pivot [m/s,
// rad/s, m], the terms of find_point_velocity (engine/kinematics.h) computed once per step
struct CarriageMotion {
  Eigen::Vector3d v, w, pivot;
};

CarriageMotion find_carriage_motion(const State& state, const Data& data, int c) {
  const CarriageState& cs = state.carriages[c];
  return {Eigen::Vector3d(cs.rate[0], cs.rate[1], cs.rate[2]),
          data.axes[c][0] * cs.rate[3] + data.axes[c][1] * cs.rate[4] +
              data.axes[c][2] * cs.rate[5],
          cs.pivot_W};
}

// the affine map from the insert frame T into a field's grid coordinates, g = A p_T + b
// [nodes]: X_FT followed by (p_F - origin) / spacing, one map per element instead of two
// transforms, a subtraction and three divisions
struct GridMap {
  Eigen::Matrix3d A;
  Eigen::Vector3d b;
  GridMap(const SignedDistanceField& f, const Eigen::Isometry3d& X_FT)
      : A(X_FT.linear() / f.spacing), b((X_FT.translation() - f.origin) / f.spacing) {}
  Eigen::Vector3d operator()(const Eigen::Vector3d& p_T) const { return A * p_T + b; }
};

}  // namespace

void finish_contact_summary(const Model& model, const std::array<double, 2>& weight,
                            const std::array<std::array<double, kNumDof>, 2>& stiffness,
                            ContactSummary& sum) {
  for (int side = 0; side < 2; ++side) {
    if (weight[side] > 0.0) sum.cop_T[side] /= weight[side];
  }
  const double area = sum.area[0] + sum.area[1];
  sum.mean_pressure = area > 0.0 ? (sum.normal_force[0] + sum.normal_force[1]) / area : 0.0;
  for (int c = 0; c < 2; ++c) {
    for (int i = 0; i < kNumDof; ++i) {
      const DofModel& dof = model.carriages[c].dofs[i];
      if (dof.mode != DofMode::kFree && dof.mode != DofMode::kForce) continue;
      sum.stiffness[c][i] = stiffness[c][i];
      if (dof.implicit) continue;  // stable in its own stiffness for any step
      sum.omega_max = std::max(sum.omega_max, std::sqrt(stiffness[c][i] / dof.mass));
    }
  }
}

namespace {

// what the reduction needs of an element in contact: centroid and normal [m, -], world;
// force on the femur [N]; elastic pressure [Pa]; penetration [m]; normal stiffness A dp/dd
// [N/m]; friction slope [N s/m] (the element's friction force on the femur is -ce slip_W)
struct ContactTerms {
  Eigen::Vector3d c_W, n_W, force_W;
  Eigen::Vector3d slip_W;  // slip velocity of the femur over the insert [m/s]
  double pressure = 0.0, penetration = 0.0, ke = 0.0, ce = 0.0;
  double coulomb = 0.0;    // mu p A, the element's full Coulomb force [N]
};

// the element loop of one step: its constants and the element arrays it reads and writes,
// gathered in one object of which each thread takes a private copy. Read through model and
// data instead, every member would be reloaded after each store (Eigen's vector stores may
// alias anything), and the search's few dozen instructions per element would double.
struct ElementLoop {
  // search: the fine and far fields, the maps into their grids, the femoral origin in T
  FieldSampler fine, far;
  GridMap to_fine, to_far;
  PairGridMap pairs_to_fine, pairs_to_far;  // the same maps for two elements at once
  double band = 0.0, far_spacing = 0.0;
  bool has_far = false;  // a model may come without the far field (hand-built test models)
  Eigen::Vector3d o_T;
  double femur_radius = 0.0, radius2 = 0.0, motion = 0.0;
  // contact: the insert pose, the carriages' motion, the laws
  Eigen::Matrix3d R_WT, R_TW;
  Eigen::Vector3d t_WT;
  CarriageMotion femur, tibia;
  ContactModel law;
  const Eigen::Vector3d* centroid_T;
  const Eigen::Vector3d* normal_T;
  const double* thickness;
  const double* area;
  // per-element results (Data)
  double* recheck_at;
  double* pressure;
  double* penetration;
  double* slip_speed;
  double* friction_viscosity;
  double* contact_stiffness;
  Eigen::Vector3d* slip_velocity_T;
  Eigen::Vector3d* element_force_W;

  ElementLoop(const Model& model, const State& state, Data& data)
      : fine(model.femur_sdf.sampler()),
        far(model.femur_far_sdf.sampler()),
        to_fine(model.femur_sdf, data.X_WF.inverse() * data.X_WT),
        to_far(model.femur_far_sdf, data.X_WF.inverse() * data.X_WT),
        pairs_to_fine(to_fine.A, to_fine.b),
        pairs_to_far(to_far.A, to_far.b),
        band(model.femur_sdf.band),
        far_spacing(model.femur_far_sdf.spacing),
        has_far(!model.femur_far_sdf.empty()),
        // F's origin in T: |p_F| = |p_T - o_T| (a rigid map keeps lengths)
        o_T(data.X_WT.inverse() * data.X_WF.translation()),
        femur_radius(model.femur_radius),
        radius2(model.femur_radius * model.femur_radius),
        motion(data.motion),
        R_WT(data.X_WT.linear()),
        R_TW(data.X_WT.linear().transpose()),
        t_WT(data.X_WT.translation()),
        femur(find_carriage_motion(state, data, 0)),
        tibia(find_carriage_motion(state, data, 1)),
        law(model.contact),
        centroid_T(model.insert.centroid_T.data()),
        normal_T(model.insert.normal_T.data()),
        thickness(model.insert.thickness.data()),
        area(model.insert.area.data()),
        recheck_at(data.recheck_at.data()),
        pressure(data.pressure.data()),
        penetration(data.penetration.data()),
        slip_speed(data.slip_speed.data()),
        friction_viscosity(data.friction_viscosity.data()),
        contact_stiffness(data.contact_stiffness.data()),
        slip_velocity_T(data.slip_velocity_T.data()),
        element_force_W(data.element_force_W.data()) {}

  // the fine field's distance at element e's centroid [m]
  [[gnu::always_inline]] double find_distance(int e) const {
    return fine.sample_grid(to_fine(centroid_T[e]));
  }
  // find_distance of elements e and f, into out[0] and out[1]: the same bits (engine/sdf_pairs.h)
  [[gnu::always_inline]] void find_distances(int e, int f, double out[2]) const {
    sample_pair(fine, pairs_to_fine, centroid_T[e], centroid_T[f], out);
  }
  // whether an element at fine distance phi lies beyond the fine band, where the coarse field
  // tells the distance
  [[gnu::always_inline]] bool is_far(double phi) const { return (phi >= band) & has_far; }
  // such an element's gap: the coarse field's distance less its interpolation error, if larger
  [[gnu::always_inline]] double find_far_gap(int e, double phi) const {
    return std::max(phi, far.sample_grid(to_far(centroid_T[e])) - far_spacing);
  }
  // find_far_gap of elements e and f at fine distances phi_e and phi_f, into gap_e and gap_f
  [[gnu::always_inline]] void find_far_gaps(int e, int f, double phi_e, double phi_f,
                                            double& gap_e, double& gap_f) const {
    double s[2];
    sample_pair(far, pairs_to_far, centroid_T[e], centroid_T[f], s);
    gap_e = std::max(phi_e, s[0] - far_spacing);
    gap_f = std::max(phi_f, s[1] - far_spacing);
  }

  // the element's distance, its next evaluation, and while in contact its pressure, slip and
  // force; writes only element e's slots. True when in contact, with the terms the reduction
  // needs in `terms`.
  [[gnu::always_inline]] bool evaluate(int e, ContactTerms& terms) const {
    const double phi = find_distance(e);
    return finish(e, phi, is_far(phi) ? find_far_gap(e, phi) : phi, terms);
  }

  // evaluate() from the element's fine distance phi and its gap (phi, or find_far_gap beyond
  // the band)
  [[gnu::always_inline]] bool finish(int e, double phi, double gap, ContactTerms& terms) const {
    const Eigen::Vector3d& c_T = centroid_T[e];
    const double d = -phi;
    if (d <= 0.0) {
      // out of contact: sleep until the motion could have closed the gap
      const double r2 = (c_T - o_T).squaredNorm();
      if (femur_radius > 0.0 && r2 > radius2) {
        // a point farther from the femoral origin than femur_radius moves proportionally more
        gap *= femur_radius / std::sqrt(r2);
      }
      recheck_at[e] = motion + kLipschitz * gap;
      if (penetration[e] != 0.0) {
        // leaving contact: clear the element's slots (they stay zero while it is out, and
        // most evaluations are of elements out of contact: five scattered stores saved)
        pressure[e] = 0.0;
        penetration[e] = 0.0;
        slip_speed[e] = 0.0;
        slip_velocity_T[e].setZero();
        element_force_W[e].setZero();
      }
      return false;
    }
    recheck_at[e] = motion;  // in contact: evaluate every step
    const Eigen::Vector3d c_W = R_WT * c_T + t_WT;
    const Eigen::Vector3d n_W = R_WT * normal_T[e];
    const double h = thickness[e];
    // relative velocity of the femoral surface over the insert at the element
    const Eigen::Vector3d v_rel = (femur.v + femur.w.cross(c_W - femur.pivot)) -
                                  (tibia.v + tibia.w.cross(c_W - tibia.pivot));
    const double closing = -v_rel.dot(n_W);  // rate of penetration [m/s]
    const Eigen::Vector3d v_slip = v_rel + closing * n_W;
    const auto [p_elastic, k_area] =
        ef_pressure_and_stiffness(law.law, law.foundation_modulus, law.exponent, d, h);
    const double p_damping = law.damping_beta * k_area * closing;
    // the damper may at most double or cancel the elastic pressure: an impact (a fast closing
    // speed) must not produce a force spike that the stable step does not cover
    const double p = p_elastic + std::clamp(p_damping, -p_elastic, p_elastic);
    const Eigen::Vector3d traction =
        p * n_W + friction_traction(law.friction, p, v_slip, law.slip_regularization);
    terms.c_W = c_W;
    terms.n_W = n_W;
    terms.force_W = area[e] * traction;
    terms.pressure = p_elastic;
    terms.penetration = d;
    terms.ke = area[e] * k_area;
    contact_stiffness[e] = terms.ke;
    terms.ce = area[e] * law.friction * p /
               std::sqrt(v_slip.squaredNorm() + law.slip_regularization * law.slip_regularization);
    pressure[e] = p_elastic;
    penetration[e] = d;
    slip_speed[e] = v_slip.norm();
    slip_velocity_T[e] = R_TW * v_slip;
    element_force_W[e] = terms.force_W;
    friction_viscosity[e] = terms.ce;
    set_friction_terms(e, terms);
    return true;
  }

  // the terms of an element that evaluate() found in contact this step, again from its slots
  // (the parallel path): the same expressions, so the same bits
  ContactTerms find_terms(int e) const {
    ContactTerms t;
    t.c_W = R_WT * centroid_T[e] + t_WT;
    t.n_W = R_WT * normal_T[e];
    t.force_W = element_force_W[e];
    t.pressure = pressure[e];
    t.penetration = penetration[e];
    t.ke = contact_stiffness[e];
    t.ce = friction_viscosity[e];
    set_friction_terms(e, t);
    return t;
  }

  // the slip and the full Coulomb force from the element's slots, in both paths (the same
  // bits for any thread count)
  [[gnu::always_inline]] void set_friction_terms(int e, ContactTerms& t) const {
    t.slip_W = R_WT * slip_velocity_T[e];
    t.coulomb = t.ce * std::sqrt(t.slip_W.squaredNorm() +
                                 law.slip_regularization * law.slip_regularization);
  }
};

// symmetric 3x3 as xx, yy, zz, xy, xz, yz
using Sym3 = std::array<double, 6>;

// S += w v v^T
inline void add_outer(Sym3& S, double w, const Eigen::Vector3d& v) {
  const Eigen::Vector3d wv = w * v;
  S[0] += wv.x() * v.x();
  S[1] += wv.y() * v.y();
  S[2] += wv.z() * v.z();
  S[3] += wv.x() * v.y();
  S[4] += wv.x() * v.z();
  S[5] += wv.y() * v.z();
}

// a^T S a
inline double quadratic_form(const Sym3& S, const Eigen::Vector3d& a) {
  return a.x() * a.x() * S[0] + a.y() * a.y() * S[1] + a.z() * a.z() * S[2] +
         2.0 * (a.x() * a.y() * S[3] + a.x() * a.z() * S[4] + a.y() * a.z() * S[5]);
}

// the tangent stiffness and the friction's viscous slope per DOF of a carriage, summed over
// the elements in contact as second moments: with r = c - pivot and u = r x n, the rotational
// DOF about axis a has stiffness sum ke (a.u)^2 = a^T (sum ke u u^T) a and friction slope
// sum ce (|a x r|^2 - (a.u)^2) = |a|^2 tr(Cr) - a^T Cr a - a^T Cu a with Cr = sum ce r r^T
// and Cu = sum ce u u^T: three 3x3 sums per element instead of nine cross and dot products
// The same second moments with the elements' full Coulomb force w = mu p A give
// sum w |J_t|^2, which bounds the friction a DOF can receive: Phi = sum w |J_t| <=
// sqrt(sum w * sum w |J_t|^2) (Cauchy-Schwarz; equal when |J_t| is the same everywhere).
struct CarriageMoments {
  Sym3 ku{}, cu{}, cr{}, wu{}, wr{};
  void add(double ke, double ce, double coulomb, const Eigen::Vector3d& r,
           const Eigen::Vector3d& n) {
    const Eigen::Vector3d u = r.cross(n);
    add_outer(ku, ke, u);
    add_outer(cu, ce, u);
    add_outer(cr, ce, r);
    add_outer(wu, coulomb, u);
    add_outer(wr, coulomb, r);
  }
};

// fixed-order reduction over the elements in contact (ascending): totals, per-condyle
// summary, moment about the world origin, and the moments of the tangent stiffness and
// friction slope for the stability monitor and the implicit friction
struct ContactReduction {
  ContactSummary sum;
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment_O = Eigen::Vector3d::Zero();
  std::array<double, 2> weight{};
  // the translational DOFs (world axes) are the same for both carriages
  std::array<double, 3> stiffness_t{}, friction_t{}, capacity_t{};
  // the friction's share of force and moment, and the total full Coulomb force sum mu p A
  Eigen::Vector3d friction_force = Eigen::Vector3d::Zero();
  Eigen::Vector3d friction_moment_O = Eigen::Vector3d::Zero();
  double coulomb = 0.0;
  std::array<CarriageMoments, 2> moments;
  std::array<Eigen::Vector3d, 2> pivots;
  // the coupled rig step's stiffness between the moved DOFs (model.coupled_rig_step)
  bool coupled = false;
  CoupledDofs coupled_dofs;
  std::array<std::array<Eigen::Vector3d, 3>, 2> axes{};
  std::array<double, 144> coupling{}, friction_coupling{};
  const SignedDistanceField* femur_sdf = nullptr;
  Eigen::Isometry3d X_FW = Eigen::Isometry3d::Identity();

  // whether a carriage has a rotational DOF that the integrator moves (free or force-driven):
  // the moments serve only those (the default rig's femur has none: its flexion is
  // prescribed, the other rotations locked), so a carriage without one skips them
  std::array<bool, 2> rotates{};

  ContactReduction(const Model& model, const State& state, const Data& data)
      : pivots{state.carriages[0].pivot_W, state.carriages[1].pivot_W},
        coupled(model.coupled_rig_step) {
    if (coupled) {
      coupled_dofs = find_coupled_dofs(model);
      axes = data.axes;
      femur_sdf = &model.femur_sdf;
      X_FW = data.X_WF.inverse();
    }
    for (int c = 0; c < 2; ++c) {
      for (int i = 3; i < kNumDof; ++i) rotates[c] = rotates[c] || is_moved(model, c, i);
    }
  }

  static bool is_moved(const Model& model, int c, int i) {
    const DofMode mode = model.carriages[c].dofs[i].mode;
    return mode == DofMode::kFree || mode == DofMode::kForce;
  }

  [[gnu::always_inline]] void add(const InsertSurface& s, int e, const ContactTerms& t) {
    for (int i = 0; i < 3; ++i) {
      // normal stiffness along the DOF's direction; friction acts on its tangential part
      stiffness_t[i] += t.ke * t.n_W[i] * t.n_W[i];
      friction_t[i] += t.ce * (1.0 - t.n_W[i] * t.n_W[i]);
      capacity_t[i] += t.coulomb * (1.0 - t.n_W[i] * t.n_W[i]);
    }
    for (int c = 0; c < 2; ++c) {
      if (rotates[c]) moments[c].add(t.ke, t.ce, t.coulomb, t.c_W - pivots[c], t.n_W);
    }
    if (coupled) {
      // the penetration grows along minus the femoral surface's outward normal
      Eigen::Vector3d grad_F = Eigen::Vector3d::Zero();
      femur_sdf->sample(X_FW * t.c_W, &grad_F);
      const double norm = grad_F.norm();
      const Eigen::Vector3d m_W =
          norm > 0.0 ? Eigen::Vector3d(-(X_FW.linear().transpose() * grad_F) / norm) : t.n_W;
      add_contact_coupling(coupled_dofs, t.ke, t.ce, t.c_W, t.n_W, m_W, axes, pivots, coupling,
                           &friction_coupling);
    }
    force += t.force_W;
    moment_O += t.c_W.cross(t.force_W);
    const Eigen::Vector3d f_friction = -t.ce * t.slip_W;
    friction_force += f_friction;
    friction_moment_O += t.c_W.cross(f_friction);
    coulomb += t.coulomb;
    const double p = t.pressure, d = t.penetration;
    const int side = s.medial[e] ? 0 : 1;
    sum.normal_force[side] += p * s.area[e];
    sum.area[side] += s.area[e];
    sum.cop_T[side] += (p * s.area[e]) * s.centroid_T[e];
    weight[side] += p * s.area[e];
    sum.peak_pressure = std::max(sum.peak_pressure, p);
    sum.max_penetration = std::max(sum.max_penetration, d);
    sum.max_penetration_ratio = std::max(sum.max_penetration_ratio, d / s.thickness[e]);
    ++sum.elements_in_contact;
  }

  // the summary into data.contact, the friction's force, slope and capacity per DOF into
  // data.friction (zero for a DOF that is neither free nor force-driven: the integrator does
  // not read it)
  void finish(const Model& model, Data& data) {
    std::array<std::array<double, kNumDof>, 2> stiffness{};
    for (int c = 0; c < 2; ++c) {
      const CarriageMoments& mc = moments[c];
      const double trace_cr = mc.cr[0] + mc.cr[1] + mc.cr[2];
      const double trace_wr = mc.wr[0] + mc.wr[1] + mc.wr[2];
      // the friction on the femur, on the tibia the reaction; its moment about the pivot
      const double sign = c == 0 ? 1.0 : -1.0;
      const Eigen::Vector3d torque =
          sign * (friction_moment_O - pivots[c].cross(friction_force));
      FrictionTerms& f = data.friction[c];
      for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d& a = data.axes[c][i];
        stiffness[c][i] = stiffness_t[i];
        stiffness[c][3 + i] = quadratic_form(mc.ku, a);
        const bool moved_t = is_moved(model, c, i), moved_r = is_moved(model, c, 3 + i);
        f.force[i] = moved_t ? sign * friction_force[i] : 0.0;
        f.secant[i] = moved_t ? friction_t[i] : 0.0;
        f.capacity[i] = moved_t ? std::sqrt(coulomb * capacity_t[i]) : 0.0;
        f.force[3 + i] = moved_r ? torque.dot(a) : 0.0;
        const double c_r =
            a.squaredNorm() * trace_cr - quadratic_form(mc.cr, a) - quadratic_form(mc.cu, a);
        f.secant[3 + i] = moved_r ? c_r : 0.0;
        const double w_r =
            a.squaredNorm() * trace_wr - quadratic_form(mc.wr, a) - quadratic_form(mc.wu, a);
        f.capacity[3 + i] = moved_r ? std::sqrt(coulomb * std::max(w_r, 0.0)) : 0.0;
      }
    }
    if (coupled) {
      data.contact_coupling = coupling;
      data.friction_coupling = friction_coupling;
    }
    sum.force_W = force;
    sum.tray_force_W = -force;
    finish_contact_summary(model, weight, stiffness, sum);
    data.contact = sum;
  }
};

}  // namespace

void calc_contact(const Model& model, const State& state, Data& data) {
  update_contact_schedule(model, data);
  const int n = static_cast<int>(data.due.size());
  const int* due = data.due.data();
  data.evaluations += n;
  data.in_contact.clear();
  const ElementLoop loop(model, state, data);
  ContactReduction reduction(model, state, data);
  if (n > kParallelAbove && model.threads > 1) {
    // element-local evaluation in parallel (each element writes only its own slots), then the
    // reduction in element order: bit-identical for any thread count
#pragma omp parallel num_threads(model.threads)
    {
      const ElementLoop local = loop;  // a private copy: its members stay in registers
      ContactTerms terms;
#pragma omp for schedule(static)
      for (int i = 0; i < n; ++i) local.evaluate(due[i], terms);
    }
    for (int i = 0; i < n; ++i) {
      const int e = due[i];
      if (data.penetration[e] > 0.0) {
        data.in_contact.push_back(e);
        reduction.add(model.insert, e, loop.find_terms(e));
      }
    }
  } else {
    // the same in batches of three passes: the fine distances of the batch, two elements at a
    // time (loads of independent elements overlap, no contact test between them to
    // mispredict); the coarse field's distances of those beyond the band (listed without a
    // branch, sampled in pairs too); then each element's sleep or contact in due order, its
    // terms going to the reduction as it is evaluated. The arithmetic per element is
    // evaluate()'s, so are the bits.
    const ElementLoop local = loop;
    ContactTerms terms;
    constexpr int kBatch = 64;
    double phi[kBatch], gap[kBatch];
    int far[kBatch];
    for (int base = 0; base < n; base += kBatch) {
      const int m = std::min(kBatch, n - base);
      const int* batch = due + base;
      int i = 0;
      for (; i + 1 < m; i += 2) local.find_distances(batch[i], batch[i + 1], phi + i);
      if (i < m) phi[i] = local.find_distance(batch[i]);
      int n_far = 0;
      for (i = 0; i < m; ++i) {
        gap[i] = phi[i];
        far[n_far] = i;
        n_far += local.is_far(phi[i]);
      }
      int k = 0;
      for (; k + 1 < n_far; k += 2) {
        const int a = far[k], b = far[k + 1];
        local.find_far_gaps(batch[a], batch[b], phi[a], phi[b], gap[a], gap[b]);
      }
      if (k < n_far) gap[far[k]] = local.find_far_gap(batch[far[k]], phi[far[k]]);
      for (int i = 0; i < m; ++i) {
        const int e = batch[i];
        if (!local.finish(e, phi[i], gap[i], terms)) continue;
        data.in_contact.push_back(e);
        reduction.add(model.insert, e, terms);
      }
    }
  }
  reduction.finish(model, data);
  const Eigen::Vector3d force = reduction.force, moment_O = reduction.moment_O;

  // generalized forces: +force on the femur, -force on the tibia
  for (int c = 0; c < 2; ++c) {
    const double sign = c == 0 ? 1.0 : -1.0;
    const Eigen::Vector3d& pivot = state.carriages[c].pivot_W;
    const Eigen::Vector3d torque = sign * (moment_O - pivot.cross(force));
    auto& Q = data.generalized[c];
    Q[0] += sign * force.x();
    Q[1] += sign * force.y();
    Q[2] += sign * force.z();
    Q[3] += torque.dot(data.axes[c][0]);
    Q[4] += torque.dot(data.axes[c][1]);
    Q[5] += torque.dot(data.axes[c][2]);
  }
}

}  // namespace kneesim::engine
