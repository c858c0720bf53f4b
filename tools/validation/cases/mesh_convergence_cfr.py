"""Mesh convergence of the stiff CFR-PEEK insert on the built-in implant and default rig, with the
implant's surfaces resolved finer than the insert mesh: the built-in femur and insert are
triangulated with implant.edge_length_mm = 0.25 (default 1 mm) and the femoral distance field
sampled at contact.sdf_spacing_mm = 0.2 (default 0.4), then the footprint-refined hex mesh
(deformable.refine = contact, 6 layers graded 0.15) at 1.0, 0.7, 0.5 and 0.35 mm. The reference
is the mesh's own next refinement (the change between the last two refinements, asked below 5 %).
One more 0.5 mm run on the default 1 mm facets and 0.4 mm field shows what limits the
convergence of the mesh_convergence case."""
import importlib.util
import os

_spec = importlib.util.spec_from_file_location(
    "kneesim_mesh_convergence_common", os.path.join(os.path.dirname(__file__), "_mesh_convergence_common.py"))
C = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(C)

TITLE = "Deformable CFR-PEEK insert mesh convergence on fine implant surfaces, built-in implant"
LONG = True  # four refined deformable cycles down to 0.35 mm (78 000 elements) and one at 0.5 mm: 10-30 minutes

GEOMETRY = ["--set", "implant.edge_length_mm=0.25", "--set", "contact.sdf_spacing_mm=0.2"]
MESHES = (("r10", C.refined("1"), "1.0 mm"), ("r07", C.refined("0.7"), "0.7 mm"),
          ("r05", C.refined("0.5"), "0.5 mm"), ("r035", C.refined("0.35"), "0.35 mm"))
NOISY = dict(C.seconds_noisy("cf", [key for key, _, _ in MESHES] + ["coarse_r05"]))


def run(v):
    C.sequence(v, "cf", "cfr-peek", [(key, GEOMETRY + extra) for key, extra, _ in MESHES], changes_from=1)
    # the same 0.5 mm mesh on the default surfaces (1 mm facets, 0.4 mm field)
    f = C.one(v, "cf_coarse_r05", "cfr-peek", C.refined("0.5"))
    for k, val in f.items():
        v.figure(f"cf_coarse_r05_{k}", val)
    for k in C.FIGS:
        v.figure(f"cf_coarse_r05_{k}_vs_fine", 100 * (f[k] / v.figures[f"cf_r05_{k}"]["value"] - 1), "%")


TABLE = (C.table("cf", "CFR-PEEK, surfaces at 0.25 mm facets and a 0.2 mm distance field",
                 [(key, label) for key, _, label in MESHES], changes_from=1)
         + "\nThe 0.5 mm mesh on the default surfaces (1 mm facets, 0.4 mm distance field), in brackets "
           "against the same mesh on the fine surfaces:\n\n" + C.HEAD
         + "| {cf_coarse_r05_elements:.0f} (0.5 mm) | {cf_coarse_r05_peak:.1f} ({cf_coarse_r05_peak_vs_fine:+.1f} %) | "
           "{cf_coarse_r05_stance_peak:.1f} ({cf_coarse_r05_stance_peak_vs_fine:+.1f} %) | "
           "{cf_coarse_r05_stance_mean:.2f} ({cf_coarse_r05_stance_mean_vs_fine:+.1f} %) | "
           "{cf_coarse_r05_area:.1f} ({cf_coarse_r05_area_vs_fine:+.1f} %) | {cf_coarse_r05_seconds:.0f} | "
           "{cf_coarse_r05_ke_pct:.2f} |\n")

# the stance mean pressure and area by the nodes' area (the table above) and inside the contact
# line (docs/theory.md, "Deformable insert")
TABLES = {"line": "\n" + C.line_table("cf", [(key, label) for key, _, label in MESHES], changes_from=1)}
