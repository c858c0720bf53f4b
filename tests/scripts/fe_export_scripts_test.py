#!/usr/bin/python3
"""tools/scripts/contact_area.py and peak_section.py on a made-up export whose answer is known in
closed form: a flat insert top (y = 0, a 20 x 20 grid of 0.5 mm quads over x, z in [0, 10] mm)
under a femur that is a plane tilted about z, y = s (x - x0), so the gap is linear in x and the
contact line is x = x0. With x0 = 3.0625 mm the line crosses the quads between x = 3.0 and 3.5
at an eighth of their width, where the script's 16 samples per quad side fall exactly, so:
- the area inside the line is x0 x 10 mm = 30.625 mm² (bilinear interpolation reproduces a
  linear gap exactly);
- the nodes' area is the tributary area of the seven columns x = 0 ... 3.0 mm, 3.25 x 10 =
  32.5 mm² (the band a quarter of an element wide beyond the line, here, on one side);
- peak_section.py puts the peak at x = 0 (the deepest penetration) with the gap -s x0.
And ccx_patch_average.py's area-weighted neighbourhood mean on the same grid: a uniform field
is its own mean at any radius; a single loaded interior node is its own peak for a radius below
the spacing and a fifth of it at the spacing (itself and its four neighbours, equal areas).
Run by ctest (tests/CMakeLists.txt) with the source tree as the first argument."""
import json
import os
import subprocess
import sys
import tempfile

SOURCE = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
H, N = 0.5, 20
X0, SLOPE, K = 3.0625, 0.01, 1000.0  # line [mm], femur tilt, penalty [N/mm]


def make_export():
    nodes, top, area, pressure = [], [], [], []
    for j in range(N + 1):          # z index
        for i in range(N + 1):      # x index
            x, z = i * H, j * H
            nodes.append([x, 0.0, z])
            top.append(len(nodes) - 1)
            a = H * H * (0.5 if i in (0, N) else 1.0) * (0.5 if j in (0, N) else 1.0)
            area.append(a)
            gap = SLOPE * (x - X0)
            pressure.append(K * max(0.0, -gap) / a)
    faces = [[j * (N + 1) + i, j * (N + 1) + i + 1, (j + 1) * (N + 1) + i + 1,
              (j + 1) * (N + 1) + i] for j in range(N) for i in range(N)]
    # the femur: one quad (two triangles) of the plane y = s (x - x0), wider than the insert,
    # wound so that its normal points down (towards the insert)
    corners = [[x, SLOPE * (x - X0), z] for x, z in ((-5, -5), (15, -5), (15, 15), (-5, 15))]
    tris = [[0, 1, 2], [0, 2, 3]]
    return {
        "format": "test", "units": {}, "implant": {}, "material": {},
        "mesh": {"nodes_mm": nodes, "elements": [], "top_faces": faces,
                 "top_face_element": [0] * len(faces), "base_nodes": [], "element_size_mm": H,
                 "grading": 1, "layers": 1},
        "contact": {"top_nodes": top, "tributary_area_mm2": area,
                    "penalty_N_per_mm": [K] * len(top), "friction": 0, "law": "",
                    "sdf_spacing_mm": 0.1},
        "femur": {"vertices_F_mm": corners, "triangles": tris},
        "instants": [{"gait_pct": 13.0, "gait_pct_requested": 13.0, "time_s": 0.13,
                      "X_TF_mm": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]],
                      "node_position_mm": nodes, "top_node_pressure_MPa": pressure,
                      "applied_axial_force_N": 0, "contact_force_on_insert_T_N": [0, 0, 0],
                      "element_von_mises_MPa": [], "element_plastic_strain": [],
                      "summary": {}}],
    }


def check_patch_average():
    import importlib.util
    import numpy as np
    spec = importlib.util.spec_from_file_location(
        "ccx_patch_average", os.path.join(SOURCE, "tools", "scripts", "ccx_patch_average.py"))
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    xz = np.array([[i * H, j * H] for j in range(N + 1) for i in range(N + 1)])
    area = np.array([H * H * (0.5 if i in (0, N) else 1.0) * (0.5 if j in (0, N) else 1.0)
                     for j in range(N + 1) for i in range(N + 1)])
    ok = check("uniform field, 1.5 mm", m.averaged_peak(np.full(len(xz), 7.0), xz, area, 1.5),
               7.0, 1e-12)
    spike = np.zeros(len(xz))
    spike[10 * (N + 1) + 10] = 20.0
    ok &= check("spike, radius below the spacing", m.averaged_peak(spike, xz, area, 0.4 * H),
                20.0, 1e-12)
    ok &= check("spike, radius at the spacing", m.averaged_peak(spike, xz, area, H), 4.0, 1e-12)
    return ok


def run(script, path):
    out = subprocess.run(["/usr/bin/python3", os.path.join(SOURCE, "tools", "scripts", script),
                          path], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"FAIL {script} exited {out.returncode}: {out.stderr}")
    return out.stdout


def check(name, value, expected, tol):
    ok = abs(value - expected) <= tol
    print("%s %s: %.6g, expected %.6g within %.2g" % ("ok  " if ok else "FAIL", name, value,
                                                      expected, tol))
    return ok


def main():
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "fe_export.json")
        with open(path, "w") as f:
            json.dump(make_export(), f)
        ok = True
        row = run("contact_area.py", path).strip().splitlines()[-1].split()
        # gait %, nodes in contact, area by nodes, area inside the line, p nodes / p line
        ok &= check("nodes in contact", float(row[1]), 7 * (N + 1), 0)
        ok &= check("area by nodes mm2", float(row[2]), 3.25 * 10.0, 0.0051)  # printed to 0.01
        ok &= check("area inside the line mm2", float(row[3]), X0 * 10.0, 0.0051)
        force = sum(K * SLOPE * (X0 - i * H) for i in range(N + 1) if i * H < X0) * (N + 1)
        ok &= check("mean pressure inside the line MPa", float(row[6]), force / (X0 * 10.0),
                    1e-3 * force / (X0 * 10.0))
        lines = run("peak_section.py", path).splitlines()
        head = lines[0].split()
        ok &= check("peak node x mm", float(head[head.index("x") + 1].rstrip(",")), 0.0, 1e-9)
        first = lines[2].split()  # along z through the peak: coordinate, femur y, insert y, gap
        ok &= check("gap at the peak mm", float(first[3]), -SLOPE * X0, 1e-3)
        ok &= check_patch_average()
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
