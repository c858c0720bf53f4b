// Numerical block-on-ring model (issue 11 item 7): the rigid ring of the Hussin 2024 rig turning
// on a deformable hex8 UHMWPE block (engine/solid), Archard wear on the block's surface nodes
// and a geometry update every `update_cycles` revolutions. `kneesim bor --model fe` writes the
// semi-analytic model's bor.csv columns from it, so that the two plot together.
//
// Geometry: the block 18 mm long (x, the sliding direction) by 12 mm high (y, top at y = 0)
// by 12 mm wide (z, the ring axis); the ring's axis along z above the block's centre, the ring
// 10 mm wide. Half the block is meshed (z >= 0, the plane z = 0 a symmetry plane: z fixed
// there) and carries half the load. The mesh is graded: `element_size` under the ring within
// the contact zone (x and y), growing by `growth` per element away from it; `axial_element_size`
// along z, halved between the ring's edge and the block's side. The base is fixed.
//
// Procedure (chosen because the contact is steady in the block's frame): the ring surface
// slides past every block point at V = omega R_c, so friction is a steady traction and the
// contact a static problem at each geometry. Each geometry is solved by dynamic relaxation with
// the knee's explicit solid (the same hex8 element and node-to-surface penalty): mass scaled to
// one stable step for every element (only equilibrium is sought), mass-proportional damping
// critical for the block's lowest compression mode, the ring a rigid body with one vertical
// degree of freedom carrying half the dead load (its mass the lumped mass of the nodes under
// it, so its frequency on the contact stays below theirs). Sliding friction mu |f_n| along the
// ring surface's velocity is applied as a dead load taken from the last solved state, and the
// geometry solved again until the friction it leaves differs from the one it used by less than
// 1 % (one extra pass at the first geometry, usually none after a wear update). Measured: the
// regularized friction of the knee (a viscosity on the slip, integrated implicitly) drives
// single surface nodes into a flutter that the mass damping does not hold (kinetic energy
// stuck at 4e-5 of the strain energy, the ring reaction never settling), as friction makes
// the contact stiffness unsymmetric; a normal dashpot on the contact nodes instead made the
// ring chatter. A geometry is solved when the ring's reaction equals the load to
// `force_tolerance` and the kinetic energy is below `kinetic_tolerance` of the strain energy;
// the next geometry starts from the last displacement field (about 600 steps instead of
// 4 000). Rejected: an implicit static solve (the element has no tangent stiffness), a
// transient rotating ring (the steady contact would be re-solved every step for nothing).
//
// Wear: Archard per surface node, h += k (f_n / A_n) S dN with S = 2 pi R_c (every block point
// sees the ring's whole circumference per revolution), f_n the node's normal contact force and
// A_n its tributary area on the whole top surface (at the ring's edge the node's recession also
// lowers the faces beyond the ring, so its force is spread over them too: the worn volume is
// then exactly k S dN times the sum of the normal forces; with the tributary area under the
// ring only, the edge nodes' high pressure gave 13 % too much volume). The node
// recedes along the reference surface's normal and the nodes of its column through the
// thickness move by the same displacement scaled by their height above the base (the column
// is re-graded, so the thin top layer never inverts). The worn volume is measured from the
// worn surface (the volume between the original top plane and the bilinear top faces,
// exact with 2 x 2 Gauss points), not summed from the wear increments: the comparison with
// k F S N then checks the load balance, the nodal wear integration and the geometry update
// together. Under Archard both the semi-analytic and the numerical volume are k F S N in
// exact arithmetic; depth, contact width and pressure are where the Winkler foundation and
// the elastic solid differ.
#pragma once

#include <functional>
#include <vector>

#include "wear/bor/bor_rig.h"
#include "wear/bor/bor_simulation.h"
#include "wear/bor/bor_wear_law.h"

namespace kneesim::bor {

struct BorFeOptions {
  double element_size = 0.1e-3;         // under the ring, along x and y [m]
  double axial_element_size = 1.0e-3;   // along the ring axis z [m]
  double fine_half_width = 2.6e-3;      // half-length of the fine zone along x [m]
  double fine_depth = 0.5e-3;           // depth of the fine zone below the top [m]
  double growth = 1.25;                 // spacing ratio of neighbouring elements beyond it [-]
  double update_cycles = 10000.0;       // revolutions between geometry updates [cycles]
  double force_tolerance = 1e-3;        // |ring reaction - load| / load at equilibrium [-]
  double kinetic_tolerance = 1e-6;      // kinetic / strain energy at equilibrium [-]
  double damping_factor = 1.0;          // mass damping over the lowest mode's estimate [-]
  int max_relax_steps = 200000;         // per geometry; beyond it the run fails (exit 1)
  int threads = 1;                      // OpenMP threads of the element loop
  double density = 945.0;               // UHMWPE [kg/m^3] (irrelevant at equilibrium)
};

// one solved geometry
struct BorFeRow {
  BorRow row;                     // the semi-analytic model's columns (volume, depth, ...)
  double contact_force = 0.0;     // vertical ring reaction, whole block [N]
  double peak_pressure = 0.0;     // over the contact, the ring's edges included [Pa]
  double centre_peak_pressure = 0.0;  // on the centre row (the ring's mid-plane z = 0) [Pa]
  double centre_line_load = 0.0;  // vertical force per length on the centre row [N/m]
  double hertz_half_width = 0.0;  // 2 sqrt(sum f x^2 / sum f) on the centre row [m]
  double wear_sum_volume = 0.0;   // sum of nodal wear depth x tributary area, whole block [m^3]
  int relax_steps = 0;            // dynamic-relaxation steps of this geometry [-]
  double kinetic_ratio = 0.0;     // kinetic / strain energy at the end [-]
};

struct BorFeMeshInfo {
  int elements = 0;               // half block [-]
  int nodes = 0;                  // [-]
  double dt = 0.0;                // relaxation step after mass scaling [s]
  double damping_alpha = 0.0;     // [1/s]
};

// progress: called after each solved geometry with the row and the mesh info
using BorFeProgress = std::function<void(const BorFeRow&, const BorFeMeshInfo&)>;

// throws InputError (one sentence naming the option, the value and the allowed range) for
// options out of range
void check_bor_fe_options(const BorFeOptions& o, const BorRig& rig);

// the Archard law (params.k) on the FE block; `cycles` ascending, >= 0: one row at each,
// with geometry updates every options.update_cycles between them. Throws std::runtime_error
// when a geometry does not reach equilibrium within max_relax_steps or an element inverts.
std::vector<BorFeRow> simulate_bor_fe(const BorRig& rig, double load, const BorWearParams& params,
                                      const std::vector<double>& cycles,
                                      const BorFeOptions& options,
                                      const BorFeProgress& progress = {});

}  // namespace kneesim::bor
