// Contact stages: search (a per-element sleep schedule over the femoral signed distance
// field) and elastic-foundation contact forces with regularized Coulomb friction (physics.md
// section 4).
//
// Search: each step bounds how far insert points can have moved relative to the femur and
// accumulates it in data.motion. With D = X_FT(n+1) X_FT(n)^-1 the step's motion seen from the
// femur, a point at p_F moves at most angle(D) |p_F| + |t_D|; the accumulated measure uses
// |p_F| = R (the femoral surface's largest radius), and an element at |p_F| > R sleeps
// proportionally less. An element found at distance phi > 0 is not looked at again until the
// motion has grown by kLipschitz * phi * min(1, R / |p_F|). Only elements in or near contact
// are sampled every step. This replaced a global Verlet list (refresh everything when the
// motion exceeds half a skin), which at ~150 mm/s of relative motion during swing refreshed
// every ~8 steps and dominated the run time. FCL built the
// distance field once; per step there is no tree traversal at all.
//
// Each insert surface element (triangle) is a spring of the elastic foundation: its centroid is
// carried into the femoral frame, the field gives the overlap d = -phi, the law gives p(d, h),
// and the force p A n acts along the insert normal. The per-element loop writes element-local
// results; the reduction into carriage forces runs afterwards in element order, so results are
// bit-identical for any thread count.
#pragma once

#include "engine/data.h"
#include "engine/model.h"
#include "engine/state.h"

namespace kneesim::engine {

// fraction of the sampled distance an element may sleep for: the trilinear field is 1-Lipschitz
// along the grid axes, and up to sqrt(3) only across creases, so 0.7 keeps a margin
inline constexpr double kLipschitz = 0.7;

// due elements above which a step evaluates them in parallel, when model.threads > 1 (one
// thread takes the batched loop, which is faster on one core and gives the same bits)
inline constexpr int kParallelAbove = 2000;

// adds to data.motion the bound on this step's relative motion of insert points seen from the
// femur (X_FT against data.X_FT_prev, which it then updates); the deformable insert's node
// schedule uses the same measure (engine/insert_solid.cpp)
void accumulate_contact_motion(const Model& model, Data& data);

// accumulates the relative motion and lists in data.due the elements to evaluate this step;
// allocation-free
void update_contact_schedule(const Model& model, Data& data);

// completes a contact summary from its fixed-order sums (per side: normal force, area and the
// pressure-weighted centre sum `weight`; per DOF: the tangent stiffness): centres of pressure,
// mean pressure and the highest contact frequency over the free DOFs (stability monitor).
// Shared by the rigid and the deformable insert.
void finish_contact_summary(const Model& model, const std::array<double, 2>& weight,
                            const std::array<std::array<double, kNumDof>, 2>& stiffness,
                            ContactSummary& sum);

// per-element pressures, slips and forces of the due elements; the summary over the elements
// in contact; adds the contact forces into data.generalized of both carriages
void calc_contact(const Model& model, const State& state, Data& data);

}  // namespace kneesim::engine
