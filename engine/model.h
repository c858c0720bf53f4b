// Model: everything a simulation reads and never writes (design.md: Model / State / Data).
// Built once by models/ from a config; shared read-only by threads and study samples.
//
// The rig is two carriages (femoral, tibial), each a 6-DOF gimbal: three translations of its
// pivot along the world axes and three rotations R = Rz(fe) * Rx(vv) * Ry(ie) about the pivot
// (flexion about the fixed z axis, varus-valgus about the floating x axis, internal-external
// about the body y axis; Grood-Suntay order). Every DOF is locked, free, prescribed by a
// waveform or driven by a waveform force, with a diagonal mass (kg or kg m^2) and a linear
// carriage damper. A diagonal generalized mass was chosen over a full rigid-body inertia
// because the carriages are fictitious masses of a quasi-static rig: what matters is that the
// stable step and the damping are known and reported, not gyroscopic coupling.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "engine/sdf.h"
#include "engine/solid/solid.h"
#include "engine/solid/surface_contact.h"
#include "engine/waveform.h"

namespace kneesim::engine {

// DOF order inside a carriage; translations are along world axes, rotations gimbal angles
enum class Dof : int { kAp = 0, kIs = 1, kMl = 2, kVv = 3, kIe = 4, kFe = 5 };
inline constexpr int kNumDof = 6;
inline constexpr std::array<const char*, kNumDof> kDofNames = {"ap", "is", "ml", "vv", "ie", "fe"};
inline bool is_rotation(int dof) { return dof >= 3; }

enum class DofMode { kLocked, kFree, kPrescribed, kForce };

enum class ContactLaw { kLinear, kNonlinear };

enum class IntegratorKind { kCentralDifference, kCvode };

enum class Carriage : int { kFemur = 0, kTibia = 1 };

// one DOF of a carriage
struct DofModel {
  DofMode mode = DofMode::kLocked;
  int channel = -1;       // waveform channel of the prescribed value or applied force; -1 none
  double scale = 1.0;     // channel units -> SI (deg->rad, mm->m) times the sign convention
  double initial = 0.0;   // value at t = 0 and the locked value [m or rad]
  double mass = 1.0;      // generalized mass [kg or kg m^2]
  double damping = 0.0;   // carriage damper [N s/m or N m s/rad]
  // a light, quasi-static DOF: its contact and restraint stiffness, contact damper and
  // carriage damper are taken at the new rate (engine/step.cpp), so its mass may lie far
  // below what an explicit step needs; it does not limit the time step
  bool implicit = false;
};

struct CarriageModel {
  std::array<DofModel, kNumDof> dofs;
  Eigen::Vector3d pivot0_W = Eigen::Vector3d::Zero();  // pivot at zero DOF values [m], world
  Eigen::Isometry3d X_BP = Eigen::Isometry3d::Identity();  // implant part frame in carriage frame
  Eigen::Vector3d load_point_B = Eigen::Vector3d::Zero();  // where applied forces act [m], body
};

// spring-gap soft-tissue restraint element acting on the tibial carriage (physics.md section 2)
// translational: acts along world x at a lever arm z_arm from the pivot, so a pair at +-d also
// restrains IE rotation; rotational: acts on the IE angle directly
enum class RestraintKind { kTranslational, kRotational };
struct RestraintSpring {
  RestraintKind kind = RestraintKind::kTranslational;
  double z_arm = 0.0;       // lever arm along z from the pivot [m] (translational only)
  double gap = 0.0;         // free play each side [m or rad]
  double k_inside = 0.0;    // stiffness inside the gap [N/m or N m/rad]
  double k_positive = 0.0;  // stiffness beyond +gap (anterior / internal) [N/m or N m/rad]
  double k_negative = 0.0;  // stiffness beyond -gap (posterior / external) [N/m or N m/rad]
};

// insert articular surface elements (triangles) in the insert frame T, struct of arrays
struct InsertSurface {
  std::vector<Eigen::Vector3d> vertices_T;   // vertices [m], T frame, n_vertices
  std::vector<Eigen::Vector3i> triangles;    // vertex indices, n_elements
  std::vector<Eigen::Vector3d> centroid_T;   // element centroids [m], n_elements
  std::vector<Eigen::Vector3d> normal_T;     // outward unit normals, n_elements
  std::vector<double> area;                  // element areas [m^2], n_elements
  std::vector<double> thickness;             // elastic layer thickness under the element [m]
  std::vector<unsigned char> medial;         // 1 when the element is on the medial side
  int size() const { return static_cast<int>(area.size()); }
};

struct ContactModel {
  ContactLaw law = ContactLaw::kNonlinear;
  double foundation_modulus = 0.0;  // K = (1-nu)E/((1+nu)(1-2nu)) [Pa]
  double exponent = 1.0;            // n of p = K g^n (engine/contact_law.h) [-]
  double friction = 0.07;           // Coulomb coefficient [-]
  double slip_regularization = 1e-3;  // eps of the regularized Coulomb law [m/s]
  double damping_beta = 0.0;        // stiffness-proportional contact damping [s]
  double runaway_fraction = 0.5;    // stop when penetration exceeds this fraction of h [-]
};

struct Model {
  std::array<CarriageModel, 2> carriages;  // indexed by Carriage
  std::vector<RestraintSpring> restraint;  // on the tibial carriage
  ContactModel contact;
  InsertSurface insert;
  solid::SolidModel insert_solid;          // deformable insert (hex8) in the T frame, its
                                           // base nodes fixed; empty: rigid insert
  solid::SurfaceContact insert_contact;    // its top-surface nodes against the femur
  std::vector<int> insert_base_nodes;      // its nodes tied to the tibial carriage, ascending
  std::vector<std::array<int, 4>> insert_top_faces;  // top quads (node ids), outputs
  std::vector<int> insert_top_face_element;          // element under each top quad
  SignedDistanceField femur_sdf;           // femoral component, F frame, fine, narrow band
  SignedDistanceField femur_far_sdf;       // coarse and wide: how long far elements may sleep
  double femur_radius = 0.0;               // max |p_F| of the femoral surface [m] (0: unknown)
  Waveform gait;                           // periodic gait waveforms
  double period = 1.0;                     // gait cycle duration [s]
  double dt = 1e-4;                        // time step [s] (from calc_stable_time_step)
  double dt_critical = 1e-4;               // estimated stability limit [s]
  IntegratorKind integrator = IntegratorKind::kCentralDifference;
  int threads = 1;                         // OpenMP threads in contact evaluation
  // the light AP and IE DOFs implicit in the contact's stiffness to every moved DOF, the heavy
  // ones central difference (engine/rig_coupling.h); false: the light DOFs implicit alone
  bool coupled_rig_step = false;

  const CarriageModel& femur() const { return carriages[0]; }
  const CarriageModel& tibia() const { return carriages[1]; }
};

}  // namespace kneesim::engine
