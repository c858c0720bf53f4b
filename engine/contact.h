// Contact stages: candidate search (Verlet list over the femoral signed distance field) and
// elastic-foundation contact forces with regularized Coulomb friction (physics.md section 4).
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

// refreshes data.candidates when the femur has moved relative to the insert by more than half
// the skin since the last refresh (or never refreshed); allocation-free
void update_contact_candidates(const Model& model, const Data& kin, Data& data);

// per-element pressures, slips and forces; the summary; adds the contact forces into
// data.generalized of both carriages
void calc_contact(const Model& model, const State& state, Data& data);

}  // namespace kneesim::engine
