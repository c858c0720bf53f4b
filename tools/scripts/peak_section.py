#!/usr/bin/python3
"""Where a deformable insert's peak pressure sits: for each instant of a `kneesim run
--export-fe-pcts ...` export, the top node of highest pressure and the section of the femoral
component (at kneesim's pose) and of the deformed insert through it, along the lateral axis z
and the anterior axis x of the tibial frame T, with the node pressures on the section.

    /usr/bin/python3 tools/scripts/peak_section.py DIR/fe_export.json [--half-width-mm 4]

Reads the gap and the pressure profile across the patch: a pressure that falls to zero at the
patch's edge is a smooth (Hertz-like) contact, whose peak converges under mesh refinement; a
pressure that is highest at the patch's edge, where the femur's section turns away from a
conforming stretch, is the edge of a conforming contact (a punch with rounded corners), whose
peak is set by the corner's radius and needs elements small against the corner's contact width.
"""
import argparse
import json
import sys

import numpy as np


def section(V, T, axis, value):
    """points where the triangles (V, T) cross the plane V[:, axis] = value"""
    s = V[T][:, :, axis] - value
    cross = ~((s > 0).all(1) | (s < 0).all(1))
    pts = []
    for tri, st in zip(T[cross], s[cross]):
        a = V[tri]
        for k in range(3):
            su, sw = st[k], st[(k + 1) % 3]
            if (su > 0) != (sw > 0):
                pts.append(a[k] + su / (su - sw) * (a[(k + 1) % 3] - a[k]))
    return np.array(pts).reshape(-1, 3)


def profile(femur_pts, tops, p, along, other, q, half):
    """at each top node on the grid line through q (within 0.1 mm): the femur's section (facing side, interpolated
    between the section points), the insert's top and the node's pressure"""
    f = femur_pts[femur_pts[:, 1] < q[1] + 5.0]  # the facing side, not the far side
    f = f[np.argsort(f[:, along])]
    on = (np.abs(tops[:, other] - q[other]) < 0.1) & (np.abs(tops[:, along] - q[along]) <= half)
    rows = []
    for n in np.flatnonzero(on)[np.argsort(tops[on, along])]:
        c = tops[n, along]
        fy = float(np.interp(c, f[:, along], f[:, 1], left=np.nan, right=np.nan)) \
            if len(f) else float("nan")
        rows.append((c, fy, tops[n, 1], p[n]))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("export", help="fe_export.json of kneesim run --export-fe-pcts")
    ap.add_argument("--half-width-mm", type=float, default=4.0,
                    help="half length of the printed sections [mm] (default 4)")
    args = ap.parse_args()
    try:
        with open(args.export) as f:
            e = json.load(f)
    except (OSError, ValueError) as err:
        sys.exit(f"peak_section.py: cannot read {args.export}: {err}")
    if args.half_width_mm <= 0 or args.half_width_mm > 50:
        sys.exit("peak_section.py: --half-width-mm %g is outside (0, 50]" % args.half_width_mm)
    V0 = np.asarray(e["femur"]["vertices_F_mm"], float)
    T = np.asarray(e["femur"]["triangles"], int)
    top = np.asarray(e["contact"]["top_nodes"], int)
    for inst in e["instants"]:
        X = np.asarray(inst["X_TF_mm"], float)
        V = V0 @ X[:3, :3].T + X[:3, 3]
        x = np.asarray(inst["node_position_mm"], float)
        p = np.asarray(inst["top_node_pressure_MPa"], float)
        tops = x[top]
        i = int(np.argmax(p))
        q = tops[i]
        print("%.1f %% of the cycle: peak %.2f MPa at the top node x %.2f, z %.2f mm (y %.2f)"
              % (inst["gait_pct"], p[i], q[0], q[2], q[1]))
        for along, other, name in ((2, 0, "z (lateral)"), (0, 2, "x (anterior)")):
            pts = section(V, T, other, q[other])
            print("  along %s through the peak: femur section y, insert top y, gap, pressure"
                  % name)
            for c, fy, iy, pp in profile(pts, tops, p, along, other, q, args.half_width_mm):
                print("    %7.2f  %7.3f  %7.3f  %6.3f  %6.1f" % (c, fy, iy, fy - iy, pp))


if __name__ == "__main__":
    main()
