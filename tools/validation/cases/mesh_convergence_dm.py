"""Mesh convergence of the deformable insert's contact pressures on the Grand Challenge DM implant
(models/examples/dm_stanmore.toml, force-controlled stanmore rig), per material, at the sequence
of the built-in implant's case (mesh_convergence): the 2 mm uniform mesh, then the
footprint-refined mesh (deformable.refine = contact, 6 layers graded 0.15) at 1.0, 0.7 and
0.5 mm. The reference is the mesh's own next refinement (the change between the last two
refinements, asked below 5 %)."""
import importlib.util
import math
import os
import struct

_spec = importlib.util.spec_from_file_location(
    "kneesim_mesh_convergence_common", os.path.join(os.path.dirname(__file__), "_mesh_convergence_common.py"))
C = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(C)

TITLE = "Deformable insert mesh convergence, DM implant"
LONG = True  # nine refined deformable cycles and three 2 mm ones: 10-30 minutes

MATS = (("uhmwpe", "uh", "UHMWPE"), ("peek", "pk", "PEEK"), ("cfr-peek", "cf", "CFR-PEEK"))
MESHES = (("r20", C.UNIFORM_2MM, "2 mm, 4 layers, uniform"), ("r10", C.refined("1"), "1.0 mm"),
          ("r07", C.refined("0.7"), "0.7 mm"), ("r05", C.refined("0.5"), "0.5 mm"))
NOISY = {k: v for _, m, _ in MATS for k, v in C.seconds_noisy(m, [key for key, _, _ in MESHES]).items()}


def median_edge_mm(path, units_to_mm=1e3):
    """Median length of the first edge of each triangle of a binary STL (the data's units: m)."""
    with open(path, "rb") as f:
        data = f.read()
    n = struct.unpack_from("<I", data, 80)[0]
    edges = sorted(math.dist(v[0:3], v[3:6]) for v in
                   (struct.unpack_from("<9f", data, 84 + 50 * i + 12) for i in range(n)))
    return edges[n // 2] * units_to_mm


def run(v):
    femur = v.require_data("gc6_dm/femoral_component.stl")
    v.figure("femur_edge_median_mm", median_edge_mm(femur), "mm")
    v.figure("insert_edge_median_mm", median_edge_mm(v.require_data("gc6_dm/tibial_insert.stl")), "mm")
    config = [v.source + "/models/examples/dm_stanmore.toml"]
    for material, m, _ in MATS:
        C.sequence(v, m, material, [(key, extra) for key, extra, _ in MESHES], config)


TABLES = {m: C.table(m, name, [(key, label) for key, _, label in MESHES]) for _, m, name in MATS}
TABLES["facets"] = ("The data's triangulations: median edge of the femoral component {femur_edge_median_mm:.2f} mm, "
                    "of the tibial insert {insert_edge_median_mm:.2f} mm.\n")
