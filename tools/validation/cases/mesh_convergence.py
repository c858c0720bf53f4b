"""Mesh convergence of the deformable insert's contact pressures on the built-in implant and default
rig, per material: the footprint-refined hex mesh (deformable.refine = contact, 6 layers graded
0.15 towards the surface) at 1.0, 0.7 and 0.5 mm surface elements, against the 2 mm uniform mesh
the calibration uses; the reference is the mesh's own next refinement (the change between the last
two refinements, asked below 5 %)."""
TITLE = "Deformable insert mesh convergence, built-in implant"
LONG = True  # nine refined deformable cycles and three 2 mm ones: 10-30 minutes

MATS = (("uhmwpe", "uh"), ("peek", "pk"), ("cfr-peek", "cf"))
SIZES = (("1", "r10"), ("0.7", "r07"), ("0.5", "r05"))
FIGS = ("peak", "stance_peak", "stance_mean", "area")


def stance(rows):
    st = [r for r in rows if r["gait_pct"] <= 60.0 and r["contact_area_mm2"] > 0]
    return {"peak": max(r["peak_pressure_MPa"] for r in st),
            "stance_peak": sum(r["peak_pressure_MPa"] for r in st) / len(st),
            "stance_mean": sum(r["mean_pressure_MPa"] for r in st) / len(st),
            "area": sum(r["contact_area_mm2"] for r in st) / len(st)}


def one(v, name, material, extra):
    d = v.kneesim(name, ["run", "--cycles", "1", "--set", "insert=deformable",
                         "--set", f"material.name={material}", "--set", "solver.threads=2"]
                  + extra + ["--no-plots", "--quiet"])
    s = v.json(d, "summary.json")
    f = stance(v.csv(d, "kinematics.csv"))
    f["elements"] = s["solid_elements"]
    f["seconds"] = s["seconds_per_cycle"]
    f["ke_pct"] = 100 * s["kinetic_to_internal_max"]
    return f


def run(v):
    for material, m in MATS:
        prev = None
        runs = [("r20", one(v, f"{m}_r20", material, ["--set", "deformable.element_size_mm=2"]))]
        for h, key in SIZES:
            runs.append((key, one(v, f"{m}_{key}", material,
                                  ["--set", f"deformable.element_size_mm={h}", "--set", "deformable.layers=6",
                                   "--set", "deformable.grading=0.15", "--set", "deformable.refine=contact"])))
        for key, f in runs:
            for k, val in f.items():
                v.figure(f"{m}_{key}_{k}", val)
        for (k0, f0), (k1, f1) in zip(runs[1:-1], runs[2:]):
            for k in FIGS:
                v.figure(f"{m}_{k1}_{k}_chg", 100 * (f1[k] / f0[k] - 1), "%")
        v.figure(f"{m}_last_max_chg", max(abs(100 * (runs[-1][1][k] / runs[-2][1][k] - 1)) for k in FIGS), "%")


def _rows(m):
    r = (f"| {{{m}_r20_elements:.0f}} (2 mm, 4 layers, uniform) | {{{m}_r20_peak:.1f}} | {{{m}_r20_stance_peak:.1f}} | "
         f"{{{m}_r20_stance_mean:.2f}} | {{{m}_r20_area:.1f}} | {{{m}_r20_seconds:.0f}} | {{{m}_r20_ke_pct:.2f}} |\n")
    r += (f"| {{{m}_r10_elements:.0f}} (1.0 mm) | {{{m}_r10_peak:.1f}} | {{{m}_r10_stance_peak:.1f}} | "
          f"{{{m}_r10_stance_mean:.2f}} | {{{m}_r10_area:.1f}} | {{{m}_r10_seconds:.0f}} | {{{m}_r10_ke_pct:.2f}} |\n")
    for key, h in (("r07", "0.7"), ("r05", "0.5")):
        r += (f"| {{{m}_{key}_elements:.0f}} ({h} mm) | {{{m}_{key}_peak:.1f}} ({{{m}_{key}_peak_chg:+.1f}} %) | "
              f"{{{m}_{key}_stance_peak:.1f}} ({{{m}_{key}_stance_peak_chg:+.1f}} %) | "
              f"{{{m}_{key}_stance_mean:.2f}} ({{{m}_{key}_stance_mean_chg:+.1f}} %) | "
              f"{{{m}_{key}_area:.1f}} ({{{m}_{key}_area_chg:+.1f}} %) | {{{m}_{key}_seconds:.0f}} | {{{m}_{key}_ke_pct:.2f}} |\n")
    return r


HEAD = ("| elements (surface size) | peak pressure (MPa) | stance mean of the frame peak (MPa) | "
        "stance mean pressure (MPa) | stance contact area (mm²) | s per cycle | kinetic / internal max (%) |\n"
        "|---|---|---|---|---|---|---|\n")

TABLES = {
    "uhmwpe": "\nUHMWPE (largest change between the last two refinements: {uh_last_max_chg:.1f} %):\n\n" + HEAD + _rows("uh"),
    "peek": "\nPEEK (largest change between the last two refinements: {pk_last_max_chg:.1f} %):\n\n" + HEAD + _rows("pk"),
    "cfr": "\nCFR-PEEK (largest change between the last two refinements: {cf_last_max_chg:.1f} %):\n\n" + HEAD + _rows("cf"),
}
