#!/usr/bin/python3
"""The deformable insert's contact area two ways, at each instant of a `kneesim run
--export-fe-pcts ...` export: the sum of the tributary areas of the top nodes with a positive
pressure (what kneesim reports, and the CalculiX cross-check's measure), and the area inside
the contact line interpolated from the nodes' gaps to the femoral component (bilinear over each
top quad, the part where the gap is negative, sampled on 16 x 16 points per quad).

    /usr/bin/python3 tools/scripts/contact_area.py DIR/fe_export.json

The first counts every boundary node's whole tributary area, a band about half an element wide
outside the contact line, so it shrinks in proportion to the element size under refinement; the
second places the line between the last node inside and the first outside, an error of second
order in the element size. The gap of a node is the vertical distance from its deformed position
up to the femur's triangles at kneesim's pose (the femur's surface, not kneesim's distance field
of it, so a node kneesim counts with a penetration of a micrometre or so may show a small
positive gap here); the mean pressure is the nodes' normal force over each area.
"""
import json
import sys

import numpy as np

SAMPLES = 16


def femur_heights(V, T, points):
    """the lowest femoral surface point on the vertical line through each point (nan: none)"""
    A, B, C = V[T[:, 0]], V[T[:, 1]], V[T[:, 2]]
    v0, v1 = B - A, C - A
    d00 = v0[:, 0] ** 2 + v0[:, 2] ** 2
    d01 = v0[:, 0] * v1[:, 0] + v0[:, 2] * v1[:, 2]
    d11 = v1[:, 0] ** 2 + v1[:, 2] ** 2
    den = d00 * d11 - d01 * d01
    ok_tri = np.abs(den) > 1e-18
    out = np.full(len(points), np.nan)
    for i, q in enumerate(points):
        w0, w2 = q[0] - A[:, 0], q[2] - A[:, 2]
        d20 = w0 * v0[:, 0] + w2 * v0[:, 2]
        d21 = w0 * v1[:, 0] + w2 * v1[:, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            b = (d11 * d20 - d01 * d21) / den
            c = (d00 * d21 - d01 * d20) / den
        a = 1.0 - b - c
        hit = ok_tri & (a >= -1e-12) & (b >= -1e-12) & (c >= -1e-12)
        if hit.any():
            out[i] = (a * A[:, 1] + b * B[:, 1] + c * C[:, 1])[hit].min()
    return out


def quad_area_xz(P):
    def tri(a, b, c):
        return 0.5 * abs((b[0] - a[0]) * (c[2] - a[2]) - (c[0] - a[0]) * (b[2] - a[2]))
    return tri(P[0], P[1], P[2]) + tri(P[0], P[2], P[3])


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.split("\n\n")[1].strip())
    try:
        with open(sys.argv[1]) as f:
            e = json.load(f)
    except (OSError, ValueError) as err:
        sys.exit(f"contact_area.py: cannot read {sys.argv[1]}: {err}")
    V0 = np.asarray(e["femur"]["vertices_F_mm"], float)
    T = np.asarray(e["femur"]["triangles"], int)
    top = np.asarray(e["contact"]["top_nodes"], int)
    tributary = np.asarray(e["contact"]["tributary_area_mm2"], float)
    faces = np.asarray(e["mesh"]["top_faces"], int)
    slot = -np.ones(max(int(top.max()), int(faces.max())) + 1, int)
    slot[top] = np.arange(len(top))
    s = (np.arange(SAMPLES) + 0.5) / SAMPLES
    U, W = np.meshgrid(s, s)
    weights = [(1 - U) * (1 - W), U * (1 - W), U * W, (1 - U) * W]  # corners in order
    print("gait %   nodes in contact   area by nodes mm²   area inside the line mm²   "
          "mean pressure by nodes / inside the line MPa")
    for inst in e["instants"]:
        X = np.asarray(inst["X_TF_mm"], float)
        V = V0 @ X[:3, :3].T + X[:3, 3]
        x = np.asarray(inst["node_position_mm"], float)[top]
        p = np.asarray(inst["top_node_pressure_MPa"], float)
        touching = p > 0.0
        if not touching.any():
            print("%6.1f   no contact" % inst["gait_pct"])
            continue
        force = float((p * tributary).sum())
        area_nodes = float(tributary[touching].sum())
        # the quads with a touching corner and their corners' gaps
        q_slots = slot[faces]
        valid = (q_slots >= 0).all(1)
        near = valid & touching[np.where(q_slots >= 0, q_slots, 0)].any(1)
        corners = np.unique(q_slots[near])
        lo, hi = x[corners].min(0) - 2.0, x[corners].max(0) + 2.0
        normal_y = np.cross(V[T[:, 1]] - V[T[:, 0]], V[T[:, 2]] - V[T[:, 0]])[:, 1]
        tmin, tmax = V[T].min(1), V[T].max(1)
        keep = ((normal_y < 0.0) & (tmin[:, 0] < hi[0]) & (tmax[:, 0] > lo[0]) &
                (tmin[:, 2] < hi[2]) & (tmax[:, 2] > lo[2]) & (tmin[:, 1] < hi[1] + 2.0))
        gap = np.full(len(top), np.nan)
        gap[corners] = femur_heights(V, T[keep], x[corners]) - x[corners, 1]
        area_line = 0.0
        for q in q_slots[near]:
            # a corner with no femur above it is outside the femur's footprint: wide open
            g = np.nan_to_num(gap[q], nan=1e3)
            if (g > 0).all():
                continue
            gi = sum(w * gc for w, gc in zip(weights, g))
            area_line += quad_area_xz(x[q]) * float((gi < 0.0).mean())
        print("%6.1f   %16d   %17.2f   %24.2f   %.2f / %.2f" % (
            inst["gait_pct"], int(touching.sum()), area_nodes, area_line,
            force / area_nodes, force / area_line if area_line > 0 else float("nan")))


if __name__ == "__main__":
    main()
