"""Mesh convergence of the deformable insert's contact pressures on the built-in implant and default
rig, per material: the footprint-refined hex mesh (deformable.refine = contact, 6 layers graded
0.15 towards the surface) at 1.0, 0.7 and 0.5 mm surface elements, against the 2 mm uniform mesh
the calibration uses; the reference is the mesh's own next refinement (the change between the last
two refinements, asked below 5 %)."""
import importlib.util
import os

_spec = importlib.util.spec_from_file_location(
    "kneesim_mesh_convergence_common", os.path.join(os.path.dirname(__file__), "_mesh_convergence_common.py"))
C = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(C)

TITLE = "Deformable insert mesh convergence, built-in implant"
LONG = True  # nine refined deformable cycles and three 2 mm ones: 10-30 minutes

MATS = (("uhmwpe", "uh", "UHMWPE", "uhmwpe"), ("peek", "pk", "PEEK", "peek"), ("cfr-peek", "cf", "CFR-PEEK", "cfr"))
MESHES = (("r20", C.UNIFORM_2MM, "2 mm, 4 layers, uniform"), ("r10", C.refined("1"), "1.0 mm"),
          ("r07", C.refined("0.7"), "0.7 mm"), ("r05", C.refined("0.5"), "0.5 mm"))
NOISY = {k: v for _, m, _, _ in MATS for k, v in C.seconds_noisy(m, [key for key, _, _ in MESHES]).items()}


def run(v):
    for material, m, _, _ in MATS:
        C.sequence(v, m, material, [(key, extra) for key, extra, _ in MESHES])


TABLES = {t: C.table(m, name, [(key, label) for key, _, label in MESHES]) for _, m, name, t in MATS}
