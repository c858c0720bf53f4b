// The hex8 element of hex8.h evaluated for kBatchLanes elements at once: the element loop's
// hot kernel (issue 11, performance).
//
// Why a batch: one element update is about 900 floating-point operations on small 3x3 and
// 8x3 arrays, too short to vectorize inside one element. Four elements side by side, each in
// one lane of a 4-wide vector, vectorize every operation with no shuffles; the reference data
// are stored lane-interleaved (structure of arrays) so that each is one aligned vector load.
//
// Same element, cheaper algebra. With the Flanagan-Belytschko vectors
//   gamma_m,a = (1/8) (h_m,a - hX_m . B_a),   hX_m = sum_b h_m,b X_b,
// the hourglass displacement and the nodal hourglass force need no gamma:
//   q_m = sum_a gamma_m,a x_a = (1/8) (sum_a h_m,a x_a - F hX_m)
//   sum_m gamma_m,a K_m q_m = (1/8) (sum_m h_m,a K_m q_m - G B_a),  G = sum_m (K_m q_m) hX_m^T
// so f_a = (V0 F S - G / 8) B_a + (1/8) sum_m h_m,a K_m q_m, where the h_m,a are +-1 (additions
// only). Exact algebra, different rounding: q is still orthogonal to every linear field, so the
// patch and rigid-motion tests hold as before. The reference data shrink from 860 to 520 bytes
// per element (B, hX, K in Voigt order, V0, node ids); stored in double: a float gradient
// would put rounding of 1e-7 into the patch test's constant strain and a float hX a spurious
// hourglass force on rigid translation, and K in float would save 20 % of the bytes for a
// conversion per use (not measured to pay; left in double).
//
// Lean elastic path: an element of a J2 material that has never yielded has E_p = 0 and
// alpha = 0 and loads neither; its trial stress is checked against the yield surface on the
// squared deviator norm (no square root), and only lanes within 1e-6 of it or beyond go
// through the scalar calc_stress (the radial return of solid_material.h, unchanged).
//
// Instruction set: the vectors are GCC vector extensions (kBatchLanes = 8 doubles), compiled
// three times, for baseline x86-64 (four SSE2 quarters), AVX2 (two halves) and AVX-512F with
// VL (one register), and chosen at run time by the CPU. All do the same IEEE operations in the same
// order (no FMA: the project builds with -ffp-contract=off and the clones do not enable
// contraction), so the results are bit-identical on every path, which
// tests/engine/solid_batch_test.cpp checks. Eight lanes halve the arithmetic instructions per
// element on AVX-512 and give the kernel 32 vector registers; the lane count is the batch's,
// not the instruction set's, so every path sees the same batches.
//
// Fused force gather: the step's form of the kernel adds each element's nodal forces straight
// into the node accumulators, lane by lane in ascending element order (calc_hex8_batch_scatter,
// Hex8Batch::scatter). A node shared with another range of elements (solid.h: the ranges the
// threads take) gets its contribution stored in a slot of its own instead, and the node pass
// sums the slots in ascending element order; so every nodal force is the sum over its elements
// in ascending element order from 0.0, whatever the ranges, bit for bit the sum the separate
// gather loop formed before. A node's accumulator is 4 doubles (x, y, z, 0), so that the
// AVX-512 path adds an element's force to it with one 4-wide load, add and store after a
// transpose of the batch's force vectors (the scalar form took three of each and a reload of
// every force from the batch buffer: about a fifth of a step, by bench_solid with the scatter
// left out); the fourth component adds 0.0 to 0.0, so every path gives the same bits.
#pragma once

#include <array>
#include <cstdint>

#include "engine/solid/hex8.h"
#include "engine/solid/solid_material.h"

namespace kneesim::engine::solid {

inline constexpr int kBatchLanes = 8;

// reference data of kBatchLanes elements, lane-interleaved ([...][lane]); a lane past the
// last element of the mesh is padding: the nodes of lane 0, zero volume, gradient, moments
// and stiffness (zero force), and never read back
struct alignas(64) Hex8Batch {
  int nodes[kHexNodes][kBatchLanes];                    // node ids
  // where the step adds each element node's force: >= 0 the node's accumulator, < 0 the
  // slot ~scatter of a node shared between ranges (make_hex8_batch: the node, one range)
  int scatter[kHexNodes][kBatchLanes];
  double volume[kBatchLanes];                           // V0 [m^3]
  double gradient[kHexNodes][3][kBatchLanes];           // B_a,j [1/m]
  double hourglass_moment[kHourglassModes][3][kBatchLanes];  // hX_m [m]
  // K_m in the reference frame, Voigt xx yy zz xy yz zx [N/m]
  double hourglass_stiffness[kHourglassModes][6][kBatchLanes];
};

// internal nodal forces of a batch [N], lane-interleaved
struct alignas(64) Hex8BatchForce {
  double f[kHexNodes][3][kBatchLanes];
};

// what one batch evaluation gives besides the forces, per lane
struct Hex8BatchResult {
  double stress[6][kBatchLanes];       // S, Voigt [Pa]
  double von_mises[kBatchLanes];       // of S [Pa]
  double det_F[kBatchLanes];           // volume ratio [-]
  double strain_energy[kBatchLanes];   // elastic [J]
  double hourglass_energy[kBatchLanes];  // [J]
  // J2 only: lanes whose plastic state changed, with the new state (valid where yielded)
  std::array<bool, kBatchLanes> yielded{};
  std::array<StressUpdate, kBatchLanes> update;
};

// the batch's reference data for `count` elements (node ids `element_nodes`, their
// make_hex8_reference data `reference`; lanes past `count` padded), X the reference positions
// of all nodes
Hex8Batch make_hex8_batch(const std::array<int, kHexNodes>* element_nodes,
                          const Hex8Reference* reference, int count, const Eigen::Vector3d* X);

// the compiled paths of the kernel; the best the CPU supports is used unless one is named
// (hex8_batch_isa: the process-wide choice, the best unless a bench set another)
enum class Hex8Isa { kBaseline, kAvx2, kAvx512 };
Hex8Isa hex8_batch_best_isa();
bool hex8_batch_supports(Hex8Isa isa);
const char* to_string(Hex8Isa isa);
Hex8Isa hex8_batch_isa();
void set_hex8_batch_isa(Hex8Isa isa);  // benches only; the paths give the same bits

// one batch at node positions x (all nodes): forces into `force`, the rest into `out`. For a
// J2 material, plastic_strain and alpha point at the batch's first element's state (`count`
// valid lanes); for an elastic one they are ignored and may be null. A pure kernel.
void calc_hex8_batch(const Hex8Batch& ref, const SolidMaterial& material,
                     const Eigen::Vector3d* x, const Sym6* plastic_strain, const double* alpha,
                     int count, Hex8BatchForce& force, Hex8BatchResult& out,
                     Hex8Isa isa = hex8_batch_isa());

// the same batch with the forces of its `count` elements added where ref.scatter says, lane by
// lane in ascending order: node_force[4 n + i] += f for scatter >= 0 (4 doubles per node: x,
// y, z and a zero pad that stays zero), slot_force[3 s + i] = f for scatter = ~s (the step's
// fused gather, file comment)
void calc_hex8_batch_scatter(const Hex8Batch& ref, const SolidMaterial& material,
                             const Eigen::Vector3d* x, const Sym6* plastic_strain,
                             const double* alpha, int count, double* node_force,
                             double* slot_force, Hex8BatchResult& out,
                             Hex8Isa isa = hex8_batch_isa());

}  // namespace kneesim::engine::solid
