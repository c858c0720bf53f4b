// The deformable solid of the engine (hex8 mesh) in the Model / State / Data split
// (design.md): SolidModel holds the mesh, material and everything precomputed from the
// reference configuration; SolidState the nodal positions and velocities and the plastic
// state of each element; SolidData the per-step scratch (nodal forces, stresses, energies)
// and the thread team. Positions are in one frame chosen by the owner (S).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/work_team.h"

#include "engine/solid/hex8.h"
#include "engine/solid/hex8_batch.h"
#include "engine/solid/solid_material.h"

namespace kneesim::engine::solid {

// per-node constraint bits: a constrained DOF moves with the prescribed velocity in SolidData
inline constexpr uint8_t kFixX = 1, kFixY = 2, kFixZ = 4, kFixAll = 7;

struct SolidModel {
  SolidMaterial material;
  std::vector<Eigen::Vector3d> reference_positions;  // X [m], n_nodes
  std::vector<std::array<int, kHexNodes>> elements;  // node ids, n_elements
  std::vector<Hex8Reference> reference;              // per element
  // the element loop's compact reference data, kBatchLanes elements per batch (hex8_batch.h)
  std::vector<Hex8Batch> batches;                    // ceil(n_elements / kBatchLanes)
  std::vector<double> nodal_mass;        // lumped mass incl. any mass scaling [kg], n_nodes
  std::vector<double> inverse_mass;      // 1 / nodal_mass [1/kg], n_nodes
  std::vector<uint8_t> constraint;       // kFix* bits, n_nodes
  // The ranges the step's two loops are cut into, one task of the WorkTeam each (solid_step.h):
  // range r is the batches [range_batch[r], range_batch[r + 1]) and the nodes [range_node[r],
  // range_node[r + 1]) (node boundaries on kNodeBlock multiples). A node whose elements all lie
  // in one range has its force summed in place by that range (Hex8Batch::scatter >= 0; the
  // range zeroes it first: range_interior); a node shared between ranges gets one slot per
  // element, slots [slot_start[n], slot_start[n + 1]) in ascending element order, summed by
  // the node loop. The ranges change where the sums are formed, never their order.
  int ranges = 1;
  std::vector<int> range_batch;          // ranges + 1
  std::vector<int> range_node;           // ranges + 1
  std::vector<int> range_interior_start; // ranges + 1
  std::vector<int> range_interior;       // nodes summed in place, by range
  std::vector<int> slot_start;           // n_nodes + 1
  int num_slots = 0;
  double physical_mass = 0.0;            // rho V [kg]
  double added_mass = 0.0;               // mass added by mass scaling [kg]
  double dt_critical = 0.0;              // min over elements of L_e / c [s] (with scaled mass)
  double damping_alpha = 0.0;            // mass-proportional damping [1/s] (0: undamped)
  int threads = 1;                       // threads of the element and node loops (resolved)

  int num_nodes() const { return static_cast<int>(reference_positions.size()); }
  int num_elements() const { return static_cast<int>(elements.size()); }
  int num_batches() const { return static_cast<int>(batches.size()); }
  bool empty() const { return elements.empty(); }
};

struct SolidState {
  std::vector<Eigen::Vector3d> position;   // x [m], n_nodes
  std::vector<Eigen::Vector3d> velocity;   // v at t - dt/2 [m/s], n_nodes
  std::vector<Sym6> plastic_strain;        // E_p (Green-Lagrange) [-], n_elements
  std::vector<double> alpha;               // equivalent plastic strain [-], n_elements
  std::vector<double> plastic_work;        // dissipated plastic work [J], n_elements
};

// what calc_solid_forces found at the current positions
enum class SolidStatus { kOk, kInverted };

// nodes per block of the kinetic-energy sum: each block is summed in node order, the blocks
// in block order, so the total does not depend on the ranges
inline constexpr int kNodeBlock = 64;

// sums over one batch's elements in lane order, summed over the batches in batch order (the
// fixed order that makes the totals independent of the thread count)
struct SolidBatchTotals {
  double strain_energy = 0.0;     // [J]
  double hourglass_energy = 0.0;  // [J]
  double plastic_work = 0.0;      // [J]
  int inverted_element = -1;      // lowest element of the batch with det F <= 0
  uint32_t yielded_lanes = 0;     // bit l: lane l's plastic state changes (J2)
};

// the WorkTeam of one SolidData (a copy of the data gets a team of its own: a team serves one
// owner thread at a time)
class SolidTeam {
 public:
  SolidTeam() = default;
  explicit SolidTeam(int threads)
      : threads_(threads), team_(threads > 1 ? std::make_unique<WorkTeam>(threads) : nullptr) {}
  SolidTeam(const SolidTeam& o) : SolidTeam(o.threads_) {}
  SolidTeam& operator=(const SolidTeam& o) {
    if (this != &o) *this = SolidTeam(o.threads_);
    return *this;
  }
  SolidTeam(SolidTeam&&) = default;
  SolidTeam& operator=(SolidTeam&&) = default;
  WorkTeam* get() const { return team_.get(); }

 private:
  int threads_ = 1;
  std::unique_ptr<WorkTeam> team_;
};

struct SolidData {
  std::vector<Eigen::Vector3d> external_force;      // applied by the owner [N], n_nodes
  std::vector<Eigen::Vector3d> prescribed_velocity; // of constrained DOFs over the step [m/s]
  // regularized contact friction on a node, integrated implicitly by step_solid: a viscosity
  // on the velocity relative to the touching body, tangential to its normal
  std::vector<double> friction_viscosity;           // [N s/m], n_nodes (0: no friction)
  std::vector<Eigen::Vector3d> friction_normal;     // unit normal of the body, n_nodes
  std::vector<Eigen::Vector3d> friction_body_velocity;  // [m/s], n_nodes
  std::vector<SolidBatchTotals> batch_totals;       // per batch
  // summed over the elements [N], n_nodes; (x, y, z, 0): the fourth component pads a node to
  // one 4-wide vector, so that the element loop adds an element's force to it with one vector
  // add and store (hex8_batch.cpp)
  std::vector<Eigen::Vector4d> internal_force;
  std::vector<double> slot_force;          // element forces on shared nodes [N], 3 num_slots
  std::vector<double> von_mises;           // of S [Pa], n_elements
  // per element, filled by calc_solid_forces (not by a step, which needs none of them)
  std::vector<Sym6> stress;                // second Piola-Kirchhoff S [Pa], n_elements
  std::vector<double> strain_energy;       // elastic, element [J], n_elements
  std::vector<double> hourglass_energy;    // [J], n_elements
  std::vector<double> jacobian_ratio;      // det F of each element [-]
  // the plastic state the current positions produce, committed by a step; J2 only, and
  // written only for the lanes of SolidBatchTotals::yielded_lanes (elsewhere the state stays)
  std::vector<Sym6> next_plastic_strain;
  std::vector<double> next_alpha;
  std::vector<double> next_plastic_work;
  SolidStatus status = SolidStatus::kOk;
  int inverted_element = -1;               // lowest element id with det F <= 0
  double kinetic_energy = 0.0;             // at the last completed step [J]
  double total_strain_energy = 0.0;        // elastic + hourglass [J]
  double total_hourglass_energy = 0.0;     // [J]
  double total_plastic_work = 0.0;         // [J]
  std::vector<double> block_kinetic_energy;  // per kNodeBlock nodes, summed in node order [J]
  SolidTeam team;                          // runs the element and node loops
};

}  // namespace kneesim::engine::solid
