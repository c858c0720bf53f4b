// Data: preallocated scratch overwritten every step (design.md). Sized once by make_data();
// step() never allocates.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "engine/model.h"
#include "engine/rotation.h"

namespace kneesim::engine {

// per-frame contact results, per condyle where it matters (index 0 medial, 1 lateral)
struct ContactSummary {
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();   // total force on the femur [N]
  Eigen::Vector3d tray_force_W = Eigen::Vector3d::Zero();  // force of the insert on the
                                         // tibial carriage [N] (rigid insert: -force_W;
                                         // deformable: the base nodes' reaction)
  std::array<double, 2> normal_force{};  // sum of normal forces per condyle [N]
  std::array<double, 2> area{};          // area of elements with p > 0 per condyle [m^2]
  std::array<Eigen::Vector3d, 2> cop_T{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
                                         // pressure-weighted centre per condyle [m], T frame
  double peak_pressure = 0.0;            // [Pa]
  double mean_pressure = 0.0;            // total normal force / total area [Pa]
  double max_penetration = 0.0;          // [m]
  double max_penetration_ratio = 0.0;    // max d / h [-]
  int elements_in_contact = 0;
  // the contact's tangent stiffness per DOF, K_i = sum_e A_e dp/dd (J_ei . n_e)^2 [N/m or
  // N m/rad], zero for DOFs the integrator does not move
  std::array<std::array<double, kNumDof>, 2> stiffness{};
  // highest natural frequency sqrt(K_i / m_i) over the free DOFs that are integrated
  // explicitly; the stability monitor [rad/s]
  double omega_max = 0.0;
};

// the regularized friction's share of one carriage's generalized forces at the current rates
// (engine/implicit_friction.h); zero for DOFs the integrator does not move
struct FrictionTerms {
  std::array<double, kNumDof> force{};     // friction force or torque on the DOF [N or N m]
  std::array<double, kNumDof> secant{};    // sum_e c_e |J_e,t|^2 [N s/m or N m s/rad]
  std::array<double, kNumDof> capacity{};  // bound on the friction the DOF can receive [N or N m]
};

struct Data {
  // contact search schedule: an element whose distance to the femur was phi when last
  // evaluated cannot touch it before the relative motion accumulated since then exceeds phi,
  // so it sleeps until `motion` passes recheck_at[e] (engine/contact.h)
  std::vector<double> recheck_at;          // motion value of the next evaluation [m], n_elements
  double motion = 0.0;                     // accumulated bound on insert-point motion [m]
  Eigen::Isometry3d X_FT_prev = Eigen::Isometry3d::Identity();
  bool schedule_valid = false;
  std::vector<int> due;                    // elements evaluated this step, ascending
  std::vector<uint64_t> due_mask;          // scratch of the schedule: bit e % 64 of word e / 64
                                           // set when element e is due
  std::vector<int> in_contact;             // elements with penetration > 0, ascending
  long evaluations = 0;                    // element evaluations so far
  double insert_radius = 0.0;              // max |centroid_T| [m], bounds rotation sweep

  // per element, valid for the elements in contact (zero elsewhere)
  std::vector<double> pressure;            // contact pressure [Pa]
  std::vector<double> penetration;         // [m]
  std::vector<double> slip_speed;          // tangential slip speed femur vs insert [m/s]
  std::vector<Eigen::Vector3d> slip_velocity_T;  // slip velocity in T [m/s]
  std::vector<Eigen::Vector3d> element_force_W;  // force on the femur [N]
  std::vector<double> friction_viscosity;  // d|friction force|/d|slip| at the slip [N s/m]
  std::vector<double> contact_stiffness;   // area x dp/dd at the penetration [N/m]

  // current kinematics
  std::array<std::array<double, kNumDof>, 2> q{};    // DOF values [m or rad]
  std::array<GimbalAngles, 2> angles{};
  std::array<std::array<Eigen::Vector3d, 3>, 2> axes{};  // gimbal axes vv, ie, fe (world)
  Eigen::Isometry3d X_WF = Eigen::Isometry3d::Identity();  // femoral part pose
  Eigen::Isometry3d X_WT = Eigen::Isometry3d::Identity();  // insert pose

  // loads at the current time
  double gait_pct = 0.0;
  std::array<std::array<double, kNumDof>, 2> applied{};      // waveform loads [N or N m]
  std::array<std::array<double, kNumDof>, 2> generalized{};  // total generalized force
  // the contact friction per DOF of each carriage, integrated implicitly by the step
  // (engine/implicit_friction.h)
  std::array<FrictionTerms, 2> friction{};
  // the restraint's tangent stiffness on the tibial DOFs [N/m or N m/rad] (AP and IE)
  std::array<double, kNumDof> restraint_stiffness{};
  Eigen::Vector3d restraint_force = Eigen::Vector3d::Zero();  // AP force, IE torque summary:
                                                              // x = AP [N], y = IE [N m]

  ContactSummary contact;
  // with model.coupled_rig_step: the contact's tangent stiffness between the moved DOFs of
  // both carriages, row-major 12x12 over engine/rig_coupling.h's slots [N/m, N or N m/rad]
  std::array<double, 144> contact_coupling{};
  // and the regularized friction's secant slopes between them, sum_e c_e J_i,t . J_j,t [N s/m ...]
  std::array<double, 144> friction_coupling{};
  solid::SolidData insert_solid;  // deformable insert scratch (engine/solid/solid.h)
  solid::SurfaceContactData insert_contact;  // its top nodes' pressures and forces
};

Data make_data(const Model& model);

}  // namespace kneesim::engine
