// The contact area inside the contact line, an output measure beside the elements' (nodes')
// area.
//
// Why: the reported contact area (ContactSummary::area) counts every element with a positive
// pressure (rigid insert) or every touching node's whole tributary area (deformable insert).
// Under load the deformable insert conforms to the femur: the nodes just outside the patch
// nearly touch and the line lies close to the last node inside, so the touching nodes' outer
// quarter-quads lie mostly outside it, a band that narrows with the element size. On the
// stiff CFR-PEEK insert the nodes' area moves by 5-7 % per refinement where the area inside
// the line moves by under 2 % (tools/scripts/contact_area.py on --export-fe-pcts exports,
// docs/validation.md). The rigid insert's elements count by their centroid (no such band);
// its line area is reported too, so that the two inserts are compared by one measure.
//
// What: the signed distance to the femoral component at the surface's vertices (nodes),
// interpolated over each element (linear over a triangle, bilinear over a quad), and the part
// of the element where it is negative. For the rigid insert's elastic foundation that part is
// exactly where its law gives a pressure (p = f(-phi)); for the deformable insert's penalty
// the line lies between the last node inside and the first outside, an error of second order
// in the element size. Evaluated at output frames only, never in step().
#pragma once

#include <array>

namespace kneesim::engine {

struct Model;
struct Data;

// the fraction of a triangle where the linear interpolation of its corner values is negative
// (closed form: the corner or corners below zero cut off at the edges' zero crossings)
double calc_triangle_negative_fraction(double a, double b, double c);

// the fraction of a bilinear quad (corner values in cyclic order) where the interpolation is
// negative, sampled at the midpoints of an n x n grid (exact 0 or 1 when all corners agree:
// a bilinear function's extremes are at its corners)
double calc_quad_negative_fraction(const std::array<double, 4>& phi, int samples);

// area inside the contact line per condyle [m^2] (index 0 medial, 1 lateral) at the pose of
// `data` (the frame's): the rigid insert's articular triangles, or the deformable insert's top
// quads at the node positions its contact was evaluated at
std::array<double, 2> calc_contact_line_area(const Model& model, const Data& data);

}  // namespace kneesim::engine
